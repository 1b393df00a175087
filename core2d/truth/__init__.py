"""Ground truth of a slice: exact reachability and metrics. Never seen by the planner."""
