"""What the coopdrive.v1 messages mean beyond their types: conventions every publisher and reader of a topic shares
(an unknown value, the vehicle reference point), so a reader need not import the service that writes them."""
