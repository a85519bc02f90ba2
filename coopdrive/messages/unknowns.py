"""How a published scene object says what it does not know, for the scene that writes it and every reader of it
(the gateway's views, Foxglove's entities). No imports: a reader loads none of the scene's filters."""

# A ScalarProperty with this confidence has no value: nothing measured it, or what did has faded.
UNKNOWN_CONFIDENCE = -1.0
# The box a reader draws for an object whose size the scene does not know (yet): a passenger car's.
DEFAULT_LENGTH_M = 4.5
DEFAULT_WIDTH_M = 1.8
