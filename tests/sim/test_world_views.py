"""world_views: every ego's outlines of the others worked out at once are the ones its view would make alone."""
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from coopdrive.services.sim.world_view import WorldView, footprints_enu, world_views
from coopdrive.v1 import sim_pb2

_coordinate = st.floats(-5000.0, 5000.0, allow_nan=False)
_vehicle = st.tuples(_coordinate, _coordinate, st.floats(-7.0, 7.0, allow_nan=False), st.floats(3.0, 18.0),
                     st.floats(1.5, 2.6))


def _truths(vehicles) -> list[sim_pb2.VehicleTruth]:
    return [sim_pb2.VehicleTruth(vehicle_id=f"v{k}", x_m=x, y_m=y, heading_rad=heading, length_m=length, width_m=width)
            for k, (x, y, heading, length, width) in enumerate(vehicles)]


@settings(max_examples=60, deadline=None)
@given(st.lists(_vehicle, min_size=1, max_size=12), st.data())
def test_every_views_outlines_are_those_it_would_make_by_itself_to_the_bit(vehicles, data):
    truths = _truths(vehicles)
    egos = data.draw(st.lists(st.sampled_from(truths), unique_by=lambda t: t.vehicle_id, min_size=1))
    for view in world_views(truths, egos, {}):
        alone = WorldView(view.ego, view.others, {}, footprints_enu(truths))
        assert [t.vehicle_id for t in view.others] == [t.vehicle_id for t in truths if t is not view.ego]
        for batched, own in ((view.outlines().corners, alone.outlines().corners),
                             (view.outlines().edges, alone.outlines().edges)):
            assert batched.shape == own.shape
            assert batched.tobytes() == own.tobytes()
        assert all(np.array_equal(a, b) for a, b in zip(view.footprints_in_ego_frame(), alone.footprints_in_ego_frame(),
                                                         strict=True))


def test_a_vehicle_alone_sees_no_outlines():
    truths = _truths([(0.0, 0.0, 0.0, 4.5, 1.8)])
    (view,) = world_views(truths, truths, {})
    assert view.others == [] and len(view.outlines()) == 0
