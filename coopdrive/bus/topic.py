"""What a topic is: its name, the message it carries, the service that publishes it and whether lockstep waits for it.

Each service declares the topics it publishes with this type in its own small declaration module
(services/<name>/topics.py, named in the services table); coopdrive.bus.topics builds the registry from them.
A declaration module imports only this module and protobuf types, so the framework can read it without
importing any of the service's code.
"""

from dataclasses import dataclass

from google.protobuf.message import Message

# In a declaration's SUBSCRIBES: the service reads every topic the others publish (the gateway observes the
# whole vehicle).
EVERY_OTHER_TOPIC = "*"


@dataclass(frozen=True)
class Topic:
    name: str
    message_type: type[Message]
    publisher: str
    # Lockstep services wait for a stepped topic's messages of a step; the others (diagnostics) are
    # only observed, so nobody waits for them and their publishers send no step markers for them.
    stepped: bool = True

    @property
    def type_name(self) -> str:
        return self.message_type.DESCRIPTOR.full_name
