"""Service runtime: life cycle, data- and time-triggered handlers, clocks, lockstep stepping."""

from coopdrive.runtime.service import Service, ServiceContext

__all__ = ["Service", "ServiceContext"]
