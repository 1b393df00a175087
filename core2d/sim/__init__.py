"""The probe simulator (§3.2): owns the geometry, returns sensor readings only."""
