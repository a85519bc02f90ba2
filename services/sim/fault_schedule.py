"""Applies a scenario's timed faults to the sensor and channel models; tells the integrator about the rest.

The state is recomputed from all active faults at every update, so overlapping faults on the same target
end cleanly (the fix mode falls back to the latest still-active downgrade, then to the configured one).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

from coopdrive.services.sim.fault_config import (CanErrorBurst, Fault, FixDowngrade, GnssJump, GnssMultipath,
                                                 GnssOutage, IclcmDrop, LidarClutter, PartnerSilent, RadarClutter,
                                                 SensorDropout, SensorName, ServiceCrash, TicketExpired, V2vCorruption,
                                                 V2vLoss)
from coopdrive.services.sim.radio_channel import RadioChannel
from coopdrive.services.sim.sensor_suite import SensorSuite

# Faults that only the integrator can carry out (processes, radio transmitters, the CAN transport, the run's PKI).
INTEGRATOR_FAULTS = (PartnerSilent, IclcmDrop, ServiceCrash, CanErrorBurst, TicketExpired)


@dataclass(frozen=True)
class FaultTransition:
    fault: Fault
    started: bool
    time_s: float


class FaultSchedule:
    def __init__(self, faults: Sequence[Fault]) -> None:
        self.faults = list(faults)
        self._active: set[int] = set()
        # The vehicles the models were last brought to the active faults for; None before the first update.
        self._applied_to: frozenset[str] | None = None

    def active(self, now_s: float) -> list[Fault]:
        return [f for f in self.faults if f.active(now_s)]

    def update(self, now_s: float, suites: Mapping[str, SensorSuite],
               channel: RadioChannel | None = None) -> list[FaultTransition]:
        """Bring the models to the faults active at now_s; returns every fault that started or ended since
        the last update (including those the models already handled)."""
        active_now = {i for i, f in enumerate(self.faults) if f.active(now_s)}
        transitions = [FaultTransition(self.faults[i], i in active_now, now_s)
                       for i in sorted(active_now ^ self._active)]
        unchanged = active_now == self._active and self._applied_to == frozenset(suites)
        self._active = active_now
        active = [self.faults[i] for i in sorted(active_now)]
        # The hooks only take values, so the same faults set them to the same values again: the work is skipped
        # unless a fault started or ended, or one active moves with time (a GNSS jump's offset).
        if not unchanged or any(isinstance(fault, GnssJump) for fault in active):
            for vehicle_id, suite in suites.items():
                self._apply_to_suite(vehicle_id, suite, active, now_s)
            self._applied_to = frozenset(suites)
        if channel is not None:
            self._apply_to_channel(channel, active)
        return transitions

    @staticmethod
    def _apply_to_suite(vehicle_id: str, suite: SensorSuite, active: Sequence[Fault], now_s: float) -> None:
        mine = [f for f in active if getattr(f, "vehicle_id", None) == vehicle_id]
        suite.gnss.set_outage(any(isinstance(f, GnssOutage) for f in mine))
        jumps = [f for f in mine if isinstance(f, GnssJump)]
        offsets = [f.offset_at(now_s) for f in jumps]
        suite.gnss.set_offset(sum(east for east, _ in offsets), sum(north for _, north in offsets))
        multipath = next((f for f in mine if isinstance(f, GnssMultipath)), None)
        suite.gnss.set_multipath(multipath.jump_m if multipath else None, multipath.hop_s if multipath else 1.0)
        clutter = [f.false_alarms_per_scan for f in mine if isinstance(f, RadarClutter)]
        suite.radar.set_clutter(max(clutter) if clutter else None)
        spray = [f.clutter_probability for f in mine if isinstance(f, LidarClutter)]
        suite.lidar.set_clutter(max(spray) if spray else None)
        downgrades = sorted((f for f in mine if isinstance(f, FixDowngrade)), key=lambda f: f.start_s)
        suite.gnss.set_fix_mode(downgrades[-1].fix_mode if downgrades else suite.gnss.config.fix_mode)
        for name in SensorName:
            dropped = any(isinstance(f, SensorDropout) and f.sensor is name for f in mine)
            if name is SensorName.CAN_STATE:
                # Error frames crowd the bus: the state frames do not get through meanwhile.
                dropped = dropped or any(isinstance(f, CanErrorBurst) for f in mine)
            suite.set_dropout(name, dropped)

    @staticmethod
    def _apply_to_channel(channel: RadioChannel, active: Sequence[Fault]) -> None:
        losses: dict[str | None, float] = {}
        for fault in active:
            if isinstance(fault, V2vLoss):
                losses[fault.vehicle_id] = max(losses.get(fault.vehicle_id, 0.0), fault.loss_probability)
        for node_id in set(channel.node_loss_probability) | set(losses):
            channel.set_loss(losses.get(node_id, 0.0), node_id)
        corruption = [f.corruption_probability for f in active if isinstance(f, V2vCorruption)]
        channel.set_corruption(max(corruption) if corruption else channel.config.corruption_probability)
