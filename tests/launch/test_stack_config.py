"""What each stack vehicle of a scenario-file run is told about itself."""

from coopdrive.launch.run import RunOptions, build_specs


def test_a_stack_may_cruise_as_fast_as_the_leader_it_follows_ever_goes(tmp_path):
    specs = {(s.vehicle_id, s.service): s.config
             for s in build_specs(RunOptions(scenario="string", stacks=2), tmp_path)}
    # The string leader oscillates +-10 km/h around 80 km/h: its followers must not be capped at 80 km/h.
    assert specs[(next(v for v, service in specs if v != "world"), "planner")]["logic"]["cruise_speed_mps"] > 24.9
