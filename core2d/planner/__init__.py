"""The paper's planner (§4): decides motions from sensor readings and its own records."""
