"""Many runs: batch manifests (:mod:`.batch`) and independent tasks on Dask (:mod:`.cluster`)."""
