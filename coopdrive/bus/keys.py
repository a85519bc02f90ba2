"""Key expressions: every message lives under coopdrive/<vehicle>/<topic>."""

from dataclasses import dataclass

ROOT = "coopdrive"
# The simulated world (clock, ground truth, run results) publishes under this vehicle id.
WORLD_ID = "world"


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

    def liveliness(self, vehicle_id: str, service: str) -> str:
        return f"{self.root}/{vehicle_id}/_alive/{service}"

    def all_liveliness(self) -> str:
        return f"{self.root}/*/_alive/*"

    def service_info(self, vehicle_id: str, service: str) -> str:
        return f"{self.root}/{vehicle_id}/_info/{service}"

    def split(self, key: str) -> tuple[str, str]:
        """Returns (vehicle_id, topic) of a key under the root."""
        parts = key.split("/", 2)
        if len(parts) < 3 or parts[0] != self.root:
            raise ValueError(f"key {key!r} is not under {self.root}/<vehicle>/<topic>")
        return parts[1], parts[2]
