"""Traffic lights for the planner: the MAPEM's ingress lanes matched to the ego, the SPATEM's phases of the ego's
signal group in stack time, and what to do at the stop line. Pure modules fed the decoded messages; no network."""
