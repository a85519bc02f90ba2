"""The simulator service: owns simulated time, moves the world of a scenario file, feeds every stack its sensors."""

from __future__ import annotations

import time

from coopdrive.bus.keys import WORLD_ID
from coopdrive.runtime.master import ClockConfig, ClockMaster, ClockSettings
from coopdrive.runtime.service import Service
from coopdrive.services.sim.config import SimConfig
from coopdrive.services.sim.scenario_feed import ScenarioFeed
from coopdrive.services.sim.service_crashes import crash_outages
from coopdrive.v1 import sim_pb2


class SimService(Service, ClockMaster.Driven):
    name = "sim"
    Config = SimConfig

    def start(self) -> None:
        config: SimConfig = self.config
        self.wall_start_s = time.monotonic()
        self.feed = ScenarioFeed(self, config.scenario_path(), config.stacks, config.radio_links,
                                 already_delayed_steps=config.feedback_delay_steps - 1, gnss_ports=config.gnss_ports)

    def stop(self) -> None:
        if getattr(self, "feed", None) is not None:
            self.feed.close()

    # ----- ClockMaster.Driven ---------------------------------------------------------------
    def clock_settings(self) -> ClockSettings:
        c: SimConfig = self.config
        return ClockSettings(**c.model_dump(include=set(ClockConfig.model_fields)),
                             feedback_delay_steps=1 + self._pipelined_steps() if c.lockstep else 1,
                             outages=crash_outages(self.feed.config.faults, c.participants, c.step_s))

    def on_outage(self, participant: str, restart: bool) -> None:
        """Tells the launcher, which owns the processes, to kill the service's process or start it again."""
        self.count("service_restarts" if restart else "service_crashes")
        self.ctx.log.info("service_crash: %s %s at %.2f s", "restarting" if restart else "killing", participant,
                          self.ctx.now_s())
        self.ctx.publish_for(WORLD_ID, "service_fault", sim_pb2.ServiceFault(participant=participant, restart=restart))

    def _pipelined_steps(self) -> int:
        return self.feed.sim.pipelined_steps

    def on_clock_started(self, wall_start_monotonic_s: float) -> None:
        self.wall_start_s = wall_start_monotonic_s

    def on_clock_failed(self, reason: str) -> None:
        """The launcher waits for a result: it gets one that says why the run never started."""
        config: SimConfig = self.config
        self.ctx.publish_for(WORLD_ID, "result", sim_pb2.RunResult(
            scenario=config.scenario, seed=config.seed, success=False, failure_reason=f"the run never started: {reason}"))
