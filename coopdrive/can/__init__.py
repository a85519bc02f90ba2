"""Vehicle CAN: the DBC, its codec and candump logging (pure logic, no transport)."""
