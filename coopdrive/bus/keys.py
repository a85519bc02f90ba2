"""Key expressions: every message lives under coopdrive/<vehicle>/<topic>."""

from collections.abc import Iterable
from dataclasses import dataclass

ROOT = "coopdrive"
# The simulated world (clock, ground truth, run results) publishes under this vehicle id.
WORLD_ID = "world"
# A lockstep clock's key carries its step's remainders by these, so a follower whose triggers run only on
# every 2nd, 5th or 10th step subscribes to just those clocks (see clock_steps).
CLOCK_MODULI = (2, 5)
EVERY_STEP = "*"


@dataclass(frozen=True)
class KeyLayout:
    root: str = ROOT

    def topic(self, vehicle_id: str, topic: str) -> str:
        return f"{self.root}/{vehicle_id}/{topic}"

    def all_topics(self, vehicle_id: str = "*") -> str:
        return f"{self.root}/{vehicle_id}/**"

    def step_done(self, vehicle_id: str, topic: str) -> str:
        """Where a lockstep service says it finished a step in which it sent nothing on `topic`.

        "@step" is a verbatim chunk: wildcards such as all_topics() never match it, so recorders and
        observers do not receive the markers.
        """
        return f"{self.root}/{vehicle_id}/@step/{topic}"

    def clock_step(self, step: int) -> str:
        """Where the simulator sends the lockstep clock of `step` to the services it steps ("@clock" is verbatim,
        like "@step": recorders take the world/clock topic instead)."""
        return self._clock_key(*(str(step % modulus) for modulus in CLOCK_MODULI))

    def clock_to_all(self) -> str:
        """Clocks every stepped service needs: each one of a run paced to the wall clock, and a step re-sent
        because a participant left."""
        return self._clock_key("all")

    def clock_steps(self, periods_in_steps: Iterable[int | None]) -> list[str]:
        """Key expressions matching the clock_step() keys of every step on which a trigger with one of these
        periods (whole steps, counted from step 0; None: not a whole number) is due."""
        patterns = {tuple("0" if period and period % modulus == 0 else EVERY_STEP for modulus in CLOCK_MODULI)
                    for period in periods_in_steps}
        # A pattern inside a wider one would only deliver its clocks twice.
        kept = [p for p in patterns if not any(q != p and all(b in (a, EVERY_STEP) for a, b in zip(p, q))
                                                 for q in patterns)]
        return sorted(self._clock_key(*pattern) for pattern in kept)

    def _clock_key(self, *chunks: str) -> str:
        return "/".join((self.root, WORLD_ID, "@clock", *chunks))

    def liveliness(self, vehicle_id: str, service: str) -> str:
        return f"{self.root}/{vehicle_id}/_alive/{service}"

    def all_liveliness(self) -> str:
        return f"{self.root}/*/_alive/*"

    def service_info(self, vehicle_id: str, service: str) -> str:
        return f"{self.root}/{vehicle_id}/_info/{service}"

    def parse(self, key: str) -> tuple[str, str] | None:
        """(vehicle_id, topic) of a key under the root; None for any other key, which a reader of a recording or
        of the bus meets and passes over (another program's keys)."""
        parts = key.split("/", 2)
        if len(parts) < 3 or parts[0] != self.root:
            return None
        return parts[1], parts[2]

    def split(self, key: str) -> tuple[str, str]:
        """(vehicle_id, topic) of a key that must be under the root; ValueError naming it otherwise."""
        parsed = self.parse(key)
        if parsed is None:
            raise ValueError(f"key {key!r} is not under {self.root}/<vehicle>/<topic>")
        return parsed
