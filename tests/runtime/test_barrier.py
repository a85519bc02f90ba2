"""StepBarrier: when a service may handle a lockstep step."""

from coopdrive.runtime.barrier import StepBarrier

PARTICIPANTS = ["ego/geolocation", "ego/scene", "ego/control", "ego/actuation"]


def control_barrier():
    barrier = StepBarrier("control")
    barrier.subscribed = {"ego/ego/state", "ego/scene"}
    barrier.depend_on("ego/geolocation")
    barrier.depend_on("ego/scene")
    return barrier


def test_a_service_waits_for_its_upstream_dependencies_of_the_same_step():
    barrier = control_barrier()
    assert barrier.missing(4, PARTICIPANTS) == ["ego/geolocation", "ego/scene"]
    barrier.mark_done("ego/geolocation", 4)
    barrier.mark_done("ego/scene", 4)
    assert barrier.missing(4, PARTICIPANTS) == []


def test_services_it_takes_no_data_from_are_never_waited_for():
    barrier = control_barrier()
    barrier.mark_done("ego/geolocation", 4)
    barrier.mark_done("ego/scene", 4)
    assert "ego/actuation" not in barrier.missing(4, PARTICIPANTS)


def test_downstream_dependencies_are_needed_one_step_behind():
    barrier = StepBarrier("sim")
    barrier.depend_on("ego/actuation")
    barrier.mark_done("ego/actuation", 6)
    assert barrier.missing(7, ["ego/actuation"]) == []
    assert barrier.missing(8, ["ego/actuation"]) == ["ego/actuation"]


def test_a_marker_promising_quiet_covers_the_steps_before_the_next_trigger():
    barrier = control_barrier()
    barrier.mark_done("ego/geolocation", 2, next_step=6)
    barrier.mark_done("ego/scene", 5)
    assert barrier.missing(5, PARTICIPANTS) == []
    assert barrier.missing(6, PARTICIPANTS) == ["ego/geolocation", "ego/scene"]


def test_a_marker_is_not_trusted_before_the_messages_it_counts_have_arrived():
    barrier = control_barrier()
    barrier.mark_done("ego/geolocation", 4, sequences={"ego/ego/state": 3, "ego/other": 9})
    barrier.mark_done("ego/scene", 4)
    assert barrier.missing(4, PARTICIPANTS) == ["ego/geolocation"]
    barrier.mark_received("ego/ego/state", 3)
    assert barrier.missing(4, PARTICIPANTS) == []


def test_a_lost_participant_no_longer_holds_anyone_back():
    barrier = control_barrier()
    barrier.mark_done("ego/scene", 4)
    assert barrier.missing(4, ["ego/scene", "ego/control"]) == []


def test_a_marker_whose_counted_message_never_came_still_blocks_but_not_when_asking_for_markers_only():
    barrier = control_barrier()
    barrier.mark_done("ego/geolocation", 4, sequences={"ego/ego/state": 7})
    barrier.mark_done("ego/scene", 4)
    barrier.mark_received("ego/ego/state", 6)
    assert barrier.missing(4, PARTICIPANTS) == ["ego/geolocation"]
    assert barrier.missing(4, PARTICIPANTS, markers_only=True) == []


def test_waits_says_what_missing_says_as_the_markers_come_in_whichever_it_found_waiting_last():
    barrier = control_barrier()
    barrier.subscribed.add("ego/ego/state")
    answers = [(barrier.waits(4, PARTICIPANTS), barrier.missing(4, PARTICIPANTS))]
    barrier.mark_done("ego/geolocation", 4, sequences={"ego/ego/state": 9})  # its message 9 still on its way
    answers.append((barrier.waits(4, PARTICIPANTS), barrier.missing(4, PARTICIPANTS)))
    barrier.mark_done("ego/scene", 4)
    answers.append((barrier.waits(4, PARTICIPANTS), barrier.missing(4, PARTICIPANTS)))
    answers.append((barrier.waits(4, PARTICIPANTS, markers_only=True), barrier.missing(4, PARTICIPANTS, True)))
    barrier.mark_received("ego/ego/state", 9)
    answers.append((barrier.waits(4, PARTICIPANTS), barrier.missing(4, PARTICIPANTS)))
    answers.append((barrier.waits(4, ["ego/scene"]), barrier.missing(4, ["ego/scene"])))
    assert answers == [(True, ["ego/geolocation", "ego/scene"]), (True, ["ego/geolocation", "ego/scene"]),
                       (True, ["ego/geolocation"]), (False, []), (False, []), (False, [])]
