import math

import pytest

from coopdrive.judging.run_messages import RunMessages
from coopdrive.judging.score import JudgingParameters, ScoreError, score_messages, score_recording
from tests.judging.synthetic import sinusoid_chain_frames, truth_at, two_car_frames, write_two_car_recording


@pytest.fixture(scope="module")
def two_car_metrics(tmp_path_factory):
    return score_recording(write_two_car_recording(tmp_path_factory.mktemp("score") / "two_cars.mcap"))


def test_the_gap_is_bumper_to_bumper_and_its_minimum_is_at_the_last_sample(two_car_metrics):
    # gap = (30 + 10 t - 1) - (12 t + 4) = 25 - 2 t, smallest at t = 1 s
    assert two_car_metrics["min_gap_m"] == pytest.approx(23.0)
    assert two_car_metrics["min_time_gap_s"] == pytest.approx(23.0 / 12.0)
    assert two_car_metrics["collisions"] == 0
    assert two_car_metrics["safety_circle_violations"] == 0


def test_spacing_error_is_the_gap_minus_six_metres_plus_one_and_a_half_seconds_of_speed(two_car_metrics):
    # 25 - 2 t - (6 + 1.5 * 12) = 1 - 2 t over t = 0, 0.1, ..., 1: 1.0, 0.8, ..., -1.0
    errors = [1.0 - 0.2 * k for k in range(11)]
    assert two_car_metrics["spacing_error_m"] == pytest.approx(sum(abs(e) for e in errors) / 11)
    assert two_car_metrics["spacing_error_rms_m"] == pytest.approx(math.sqrt(sum(e * e for e in errors) / 11))
    assert two_car_metrics["spacing_error_bias_m"] == pytest.approx(0.0, abs=1e-9)
    assert two_car_metrics["spacing_error_max_m"] == pytest.approx(1.0)
    assert two_car_metrics["spacing_error_p95_m"] == pytest.approx(1.0)
    assert two_car_metrics["spacing_error_sd_m"] == pytest.approx(2 * math.sqrt(0.1))


def test_speed_error_is_the_followers_speed_minus_its_predecessors_in_kmh(two_car_metrics):
    assert two_car_metrics["speed_error_kmh"] == pytest.approx(7.2)
    assert two_car_metrics["speed_error_bias_kmh"] == pytest.approx(7.2)
    assert two_car_metrics["speed_error_max_kmh"] == pytest.approx(7.2)
    assert two_car_metrics["speed_error_sd_kmh"] == pytest.approx(0.0, abs=1e-9)


def test_comfort_and_lateral_figures_are_those_of_the_automated_follower(two_car_metrics):
    assert two_car_metrics["max_abs_accel_mps2"] == pytest.approx(1.0)
    assert two_car_metrics["rms_jerk_mps3"] == pytest.approx(1.0)
    assert two_car_metrics["lateral_error_m"] == pytest.approx(0.1)
    assert two_car_metrics["lateral_error_max_m"] == pytest.approx(0.1)


def test_position_rmse_compares_the_ego_state_with_the_truth_of_the_same_vehicle(two_car_metrics):
    assert two_car_metrics["position_rmse_m"] == pytest.approx(0.5)


def test_an_object_id_change_for_the_same_true_vehicle_is_one_identity_switch(two_car_metrics):
    assert two_car_metrics["id_switches"] == 1


def test_counts_are_integers_and_the_truth_samples_are_reported(two_car_metrics):
    assert two_car_metrics["truth_samples"] == 11
    assert two_car_metrics["truth_missing_samples"] == 0
    assert two_car_metrics["truth_longest_gap_s"] == pytest.approx(0.1)
    assert two_car_metrics["truth_duration_s"] == pytest.approx(1.0)
    assert all(isinstance(two_car_metrics[key], int) for key in ("collisions", "safety_circle_violations",
                                                                 "id_switches"))


def test_a_recording_without_ego_states_nor_scenes_has_no_position_rmse_nor_id_switches(tmp_path):
    from coopdrive.recording.writer import McapRecorder
    from tests.judging.synthetic import two_car_frames

    recorder = McapRecorder(tmp_path / "truth.mcap")
    for t, vehicles in two_car_frames():
        recorder.write("coopdrive/world/ground_truth", truth_at(t, vehicles))
    recorder.close()
    metrics = score_recording(tmp_path / "truth.mcap")
    assert "position_rmse_m" not in metrics and "id_switches" not in metrics
    assert metrics["min_gap_m"] == pytest.approx(23.0)


def test_vehicles_overlapping_for_a_while_count_as_one_collision():
    messages = RunMessages()
    for k in range(5):
        overlap = 1 <= k <= 3
        messages.add("coopdrive/world/ground_truth", truth_at(k * 0.1, [
            dict(vehicle_id="a", x_m=10.0, y_m=0.0), dict(vehicle_id="b", x_m=7.0 if overlap else 0.0, y_m=0.0)]))
    metrics = score_messages(messages)
    assert metrics["collisions"] == 1
    assert metrics["min_gap_m"] == pytest.approx(-2.0)


def test_messages_arriving_out_of_order_are_scored_in_sample_time_order():
    frames = [(t, [dict(vehicle_id="a", x_m=t, y_m=0.0, accel_mps2=t)]) for t in (0.0, 0.1, 0.2)]
    in_order, shuffled = RunMessages(), RunMessages()
    for t, vehicles in frames:
        in_order.add("coopdrive/world/ground_truth", truth_at(t, vehicles))
    for t, vehicles in reversed(frames):
        shuffled.add("coopdrive/world/ground_truth", truth_at(t, vehicles))
    assert score_messages(shuffled) == score_messages(in_order)


def test_string_gain_of_a_sinusoid_chain_is_the_largest_amplitude_ratio_leader_first():
    messages = RunMessages()
    for t, vehicles in sinusoid_chain_frames([2.0, 1.5, 1.2], frequency_hz=0.2):
        messages.add("coopdrive/world/ground_truth", truth_at(t, vehicles))
    metrics = score_messages(messages, JudgingParameters(string_frequency_hz=0.2))
    assert metrics["string_gain"] == pytest.approx(max(1.5 / 2.0, 1.2 / 1.5), rel=1e-6)


def test_an_amplifying_chain_has_a_string_gain_above_one():
    messages = RunMessages()
    for t, vehicles in sinusoid_chain_frames([1.0, 1.3], frequency_hz=0.25):
        messages.add("coopdrive/world/ground_truth", truth_at(t, vehicles))
    assert score_messages(messages, JudgingParameters(string_frequency_hz=0.25))["string_gain"] == \
        pytest.approx(1.3, rel=1e-6)


def test_a_recording_without_ground_truth_cannot_be_scored(tmp_path):
    from coopdrive.recording.writer import McapRecorder

    McapRecorder(tmp_path / "empty.mcap").close()
    with pytest.raises(ScoreError, match="ground_truth"):
        score_recording(tmp_path / "empty.mcap")


def test_v2x_figures_come_from_each_vehicles_last_status_when_there_is_one():
    from coopdrive.v1 import v2x_pb2
    from tests.judging.synthetic import two_car_frames

    messages = RunMessages()
    for t, vehicles in two_car_frames():
        messages.add("coopdrive/world/ground_truth", truth_at(t, vehicles))
    assert not any(key.startswith("v2x_") for key in score_messages(messages))
    for vehicle_id, sent, ratio, delay_s in (("leader", 10, 0.9, 0.1), ("follower", 12, 0.8, 0.3)):
        early = v2x_pb2.V2xStatus(packets_sent=1)
        early.header.sample_time_s = 0.5
        late = v2x_pb2.V2xStatus(packets_sent=sent, packets_received=sent - 1, rejected_by_reason={"malformed_gn": 2})
        late.header.sample_time_s = 1.0
        late.stations.add(station_id=1, reception_ratio=ratio, update_delay_p95_s=delay_s, messages_received=sent)
        messages.add(f"coopdrive/{vehicle_id}/v2x/status", late)
        messages.add(f"coopdrive/{vehicle_id}/v2x/status", early)
    metrics = score_messages(messages)
    assert (metrics["v2x_packets_sent"], metrics["v2x_packets_received"], metrics["v2x_packets_rejected"]) == \
        (22, 20, 4)
    assert metrics["v2x_reception_ratio_min"] == pytest.approx(0.8)
    assert metrics["v2x_update_delay_p95_max_s"] == pytest.approx(0.3)


def test_a_stack_whose_packets_every_other_stack_refuses_has_no_listeners_and_the_refusals_are_counted():
    from coopdrive.v1 import v2x_pb2
    from tests.judging.synthetic import two_car_frames

    messages = RunMessages()
    for t, vehicles in two_car_frames():
        for vehicle, station_id in zip(vehicles, (3001, 3002)):
            vehicle["station_id"] = station_id
        messages.add("coopdrive/world/ground_truth", truth_at(t, vehicles))
    # the leader (3001) refuses everything of the follower's (3002) as untrusted; the follower hears the leader
    leader = v2x_pb2.V2xStatus(rejected_by_reason={"unknown_issuer": 7, "untrusted": 5, "certificate_expired": 2})
    leader.stations.add(station_id=3002, messages_received=0, messages_refused_by_security=12)
    follower = v2x_pb2.V2xStatus()
    follower.stations.add(station_id=3001, messages_received=40, reception_ratio=0.9)
    messages.add("coopdrive/leader/v2x/status", leader)
    messages.add("coopdrive/follower/v2x/status", follower)
    metrics = score_messages(messages)
    assert (metrics["v2v_listeners_leader"], metrics["v2v_listeners_follower"]) == (1.0, 0.0)
    assert metrics["v2v_unheard_stacks"] == 1
    assert (metrics["v2x_rejected_untrusted"], metrics["v2x_rejected_certificate_expired"]) == (12, 2)
    # the refused station has no link to judge: the worst reception is the heard one's
    assert metrics["v2x_reception_ratio_min"] == pytest.approx(0.9)


def test_an_ego_state_that_says_it_is_lost_is_left_out_of_the_position_rmse():
    from coopdrive.v1 import ego_pb2

    messages = RunMessages()
    for k in range(3):
        messages.add("coopdrive/world/ground_truth", truth_at(k * 0.1, [dict(vehicle_id="a", x_m=100.0, y_m=0.0)]))
        state = ego_pb2.EgoState(x_m=100.2, y_m=0.0, mode=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE)
        if k == 0:
            state = ego_pb2.EgoState(mode=ego_pb2.LOCALISATION_MODE_LOST)  # before the first fix: at 0, 0
        state.header.sample_time_s = k * 0.1
        messages.add("coopdrive/a/ego/state", state)
    assert score_messages(messages)["position_rmse_m"] == pytest.approx(0.2)


def test_a_platoon_named_beyond_the_vehicles_of_the_run_is_judged_on_those_present():
    frames = sinusoid_chain_frames([1.0, 0.5], frequency_hz=0.2)
    messages = RunMessages()
    for t, vehicles in frames:
        messages.add("coopdrive/world/ground_truth", truth_at(t, vehicles))
    present = [v["vehicle_id"] for v in frames[0][1]]
    metrics = score_messages(messages, JudgingParameters(platoon=(*present, "v9"), string_frequency_hz=0.2))
    assert metrics["string_gain"] == pytest.approx(0.5, abs=0.05)


def test_a_pair_s_reception_ratio_counts_only_while_its_sender_sends_so_a_roadside_unit_that_stopped_is_not_zero():
    from coopdrive.v1 import v2x_pb2
    from tests.judging.synthetic import two_car_frames

    messages = RunMessages()
    for t, vehicles in two_car_frames():
        messages.add("coopdrive/world/ground_truth", truth_at(t, vehicles))
    status = v2x_pb2.V2xStatus()
    # the roadside unit stopped long ago: its window is empty (ratio 0) but it was heard 95 of 100 slots
    status.stations.add(station_id=1, messages_received=95, reception_ratio=0.0, periodic_received_total=95,
                        periodic_expected_total=100)
    status.stations.add(station_id=2, messages_received=80, reception_ratio=0.9, periodic_received_total=80,
                        periodic_expected_total=80)
    messages.add("coopdrive/follower/v2x/status", status)
    metrics = score_messages(messages)
    assert metrics["v2x_reception_ratio_min"] == pytest.approx(0.95)
    assert metrics["v2x_reception_ratio_mean"] == pytest.approx(0.975)
    assert metrics["v2x_reception_pairs"] == 2


def test_a_recording_that_lost_ground_truth_says_how_many_samples_and_the_longest_gap():
    frames = [truth_at(t, vehicles) for t, vehicles in two_car_frames(steps=60)]
    kept = [frame for frame in frames if not 1.05 < frame.header.sample_time_s < 4.95]
    metrics = score_messages(RunMessages(truth=kept))
    assert metrics["truth_samples"] == 22 and metrics["truth_missing_samples"] == 39
    assert metrics["truth_longest_gap_s"] == pytest.approx(4.0)
