"""The HDF5 archive, the only place that touches h5py: writing and reading a scene's
archive (:mod:`.store`), the validating reader's checks (:mod:`.check`), low-level
encoding (:mod:`.h5io`) and the audit's archive (:mod:`.audit`)."""
