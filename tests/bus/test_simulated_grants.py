"""A simulated vehicle's grants (`coopdrive pki bus --simulated`, coopdrive/bus/simulated_grant.py): the simulator
gets its own, and every service hears the world and the lockstep's markers of what it reads."""

from coopdrive.bus.simulated_grant import simulated_grants


def grant_of(subject: str):
    return next(grant for grant in simulated_grants("ego", ("laptop",)) if grant.subject == subject)


def test_the_simulator_puts_the_world_and_its_sensors_on_the_vehicle_and_reads_its_commands():
    sim = grant_of("sim")
    assert {"coopdrive/world/**", "coopdrive/world/@clock/**", "coopdrive/ego/gnss/fix",
            "coopdrive/ego/@step/gnss/fix"} <= set(sim.puts)
    assert "coopdrive/ego/clock" not in sim.puts and "coopdrive/ego/control/command" not in sim.puts
    assert {"coopdrive/ego/can/command", "coopdrive/ego/@step/can/command"} <= set(sim.subscriptions)


def test_a_service_puts_the_markers_of_its_topics_and_hears_the_clock_and_the_markers_of_what_it_reads():
    control = grant_of("control")
    assert "coopdrive/ego/@step/control/command" in control.puts
    assert "coopdrive/ego/@step/planner/behaviour" not in control.puts
    assert {"coopdrive/world/@clock/**", "coopdrive/ego/@step/planner/behaviour"} <= set(control.subscriptions)


def test_an_observer_on_a_simulated_bus_hears_the_world_and_still_puts_nothing():
    laptop = grant_of("laptop")
    assert "coopdrive/world/**" in laptop.subscriptions and laptop.puts == ()
