"""Every declared transition of every planner machine, and every timeout escape, is driven by a test.

The drivers modules map each (machine, from, event, to) to a driver that brings a real Planner to the source
state by real inputs and fires the transition with real inputs. A transition declared without a driver, or a
driver left for a transition no longer declared, fails the first test; a driver that no longer fires its
transition fails the second.
"""

import emergency_drivers
import intersection_drivers
import lights_drivers
import merge_drivers
import platoon_drivers
import pytest
from drivers import TIMEOUT, Key, fired

from coopdrive.services.planner.engine import MachineSpec
from coopdrive.services.planner.export_graphs import machine_specs

DRIVERS = {**platoon_drivers.DRIVERS, **merge_drivers.DRIVERS, **intersection_drivers.DRIVERS,
           **emergency_drivers.DRIVERS, **lights_drivers.DRIVERS}


def declared(spec: MachineSpec) -> set[Key]:
    events = {(spec.name, t.source.name, t.event.name, t.target.name) for t in spec.transitions}
    escapes = {(spec.name, s.state.name, TIMEOUT, s.escape.name) for s in spec.states if s.timeout_s is not None}
    return events | escapes


def key_id(key: Key) -> str:
    machine, source, event, target = key
    return f"{machine}:{source}-{event}->{target}"


def test_the_driver_table_covers_exactly_the_declared_transitions_and_timeout_escapes():
    wanted = set().union(*(declared(spec) for spec in machine_specs()))
    missing, extra = sorted(wanted - set(DRIVERS)), sorted(set(DRIVERS) - wanted)
    assert not missing, f"declared but driven by no test: {missing}"
    assert not extra, f"driven but not declared: {extra}"


@pytest.mark.parametrize("key", sorted(DRIVERS), ids=key_id)
def test_each_driver_fires_its_transition_through_the_planner_from_real_inputs(key: Key):
    machine, source, event, target = key
    _, state = DRIVERS[key]()
    assert state.machine == machine
    story = [(t.time_s, t.from_state, t.event, t.to_state, t.forced) for t in state.recent_transitions]
    assert fired(state, source, event, target) is not None, story
    assert not any(t.forced for t in state.recent_transitions), story
