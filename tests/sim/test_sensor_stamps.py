"""What the simulator hands a stack: sensor data stamped as a time-synchronised sensor stamps it, with the time
it looked at the world, so that its latency is not an error the stack cannot know of."""

import pytest

from coopdrive.bus.keys import WORLD_ID
from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.sim.config import SimConfig
from coopdrive.services.sim.sensor_config import CameraConfig, LidarConfig
from coopdrive.services.sim.service import SimService

STEP_S = 0.02


@pytest.fixture(scope="module")
def published():
    ctx = MemoryContext(vehicle_id=WORLD_ID, service_name="sim")
    service = SimService(SimConfig(scenario="follow", stacks=["ego"]), ctx)
    service.start()
    try:
        for k in range(100):
            ctx.advance_to(k * STEP_S)
    finally:
        service.stop()
    return ctx


@pytest.mark.parametrize("topic, latency_s", [("lidar/scan", LidarConfig().timing.latency_s),
                                               ("camera/frame", CameraConfig().timing.latency_s)])
def test_a_lidar_scan_and_a_camera_frame_reach_the_stack_stamped_when_they_were_sampled_not_when_delivered(
        published, topic, latency_s):
    messages = published.messages(topic, "ego")
    assert len(messages) > 10
    delays_s = [m.header.sent_time_s - m.header.sample_time_s for m in messages]
    assert min(delays_s) >= latency_s - 1e-9
