"""The originating side of DENM (EN 302 637-3 section 8): trigger, update, cancel, repeat, expire.

Pure logic. The caller describes the event as a DenmContent (situation, location, event position,
relevance, optional containers, validity); the manager owns the management fields: action id (originating
station + sequence number), detection and reference times, termination and the repetition schedule.
"""

from __future__ import annotations

from dataclasses import dataclass

from coopdrive.v2x.generation import TIME_EPSILON_S
from coopdrive.v2x.mapping.denm import DEFAULT_VALIDITY_DURATION_S
from coopdrive.v2x.timebase import MS_PER_S
from coopdrive.v1 import its_pb2

SEQUENCE_NUMBER_MODULUS = 65_536


@dataclass(frozen=True)
class ActionId:
    originating_station_id: int
    sequence_number: int


class UnknownActionError(KeyError):
    """update or cancel of an event this station does not (or no longer) originate."""


@dataclass
class _Event:
    content: its_pb2.DenmContent
    repetition_interval_s: float | None
    repeat_until_s: float
    next_send_s: float


class DenmManager:
    def __init__(self, station_id: int, station_type: int, protocol_version: int):
        self.station_id = station_id
        self.station_type = station_type
        self.protocol_version = protocol_version
        self._events: dict[ActionId, _Event] = {}
        self._next_sequence = 0

    @property
    def active(self) -> list[ActionId]:
        return list(self._events)

    def content(self, action: ActionId) -> its_pb2.DenmContent:
        return self._event(action).content

    def trigger(self, event: its_pb2.DenmContent, now_s: float, tai_ms: int,
                repetition_interval_s: float | None = None, repetition_duration_s: float | None = None) -> ActionId:
        """A new event: a DENM now, then every repetition_interval_s for repetition_duration_s
        (default: its validity). repetition_interval_s None: sent once."""
        action = ActionId(self.station_id, self._next_sequence)
        self._next_sequence = (self._next_sequence + 1) % SEQUENCE_NUMBER_MODULUS
        content = its_pb2.DenmContent()
        content.CopyFrom(event)
        content.protocol_version = self.protocol_version
        content.station_id = self.station_id
        content.station_type = self.station_type
        content.originating_station_id = action.originating_station_id
        content.sequence_number = action.sequence_number
        content.termination = its_pb2.DENM_TERMINATION_NONE
        if not content.validity_duration_s:
            content.validity_duration_s = DEFAULT_VALIDITY_DURATION_S
        if not content.detection_time_tai_ms:
            content.detection_time_tai_ms = tai_ms
        content.reference_time_tai_ms = tai_ms
        if repetition_interval_s is not None:
            content.transmission_interval_s = repetition_interval_s
        duration_s = content.validity_duration_s if repetition_duration_s is None else repetition_duration_s
        self._events[action] = _Event(content, repetition_interval_s, now_s + duration_s, now_s)
        return action

    def update(self, action: ActionId, event: its_pb2.DenmContent, now_s: float, tai_ms: int) -> None:
        """New content for the same event: a new reference time, sent at once, repetitions continue."""
        current = self._event(action)
        content = its_pb2.DenmContent()
        content.CopyFrom(event)
        for name in ("protocol_version", "station_id", "station_type", "originating_station_id", "sequence_number",
                     "termination"):
            setattr(content, name, getattr(current.content, name))
        content.ClearField("transmission_interval_s")
        if current.content.HasField("transmission_interval_s"):
            content.transmission_interval_s = current.content.transmission_interval_s
        if not content.validity_duration_s:
            content.validity_duration_s = current.content.validity_duration_s
        if not content.detection_time_tai_ms:
            content.detection_time_tai_ms = current.content.detection_time_tai_ms
        content.reference_time_tai_ms = tai_ms
        current.content = content
        current.next_send_s = now_s

    def cancel(self, action: ActionId, now_s: float, tai_ms: int, repetition_duration_s: float = 1.0) -> None:
        """The event is over: cancellation DENMs for repetition_duration_s, then the action is forgotten."""
        current = self._event(action)
        current.content.termination = its_pb2.DENM_TERMINATION_CANCELLATION
        current.content.reference_time_tai_ms = tai_ms
        current.repeat_until_s = now_s + repetition_duration_s
        current.next_send_s = now_s

    def due(self, now_s: float, tai_ms: int) -> list[its_pb2.DenmContent]:
        """DENMs to send now. Events past their validity, and cancelled ones once repeated, are dropped."""
        sending: list[its_pb2.DenmContent] = []
        for action, event in list(self._events.items()):
            content = event.content
            expired = tai_ms > content.detection_time_tai_ms + content.validity_duration_s * MS_PER_S
            repeating = now_s <= event.repeat_until_s + TIME_EPSILON_S
            cancelled = content.termination != its_pb2.DENM_TERMINATION_NONE
            if expired or (cancelled and not repeating and now_s >= event.next_send_s):
                del self._events[action]
                continue
            if now_s + TIME_EPSILON_S < event.next_send_s or not repeating:
                continue
            sending.append(content)
            if event.repetition_interval_s is None:
                event.next_send_s = float("inf")
                if cancelled:
                    del self._events[action]
            else:
                event.next_send_s = max(event.next_send_s + event.repetition_interval_s, now_s)
        return sending

    def _event(self, action: ActionId) -> _Event:
        try:
            return self._events[action]
        except KeyError:
            raise UnknownActionError(f"no active DENM event {action}") from None
