"""How much an archive may hold: the validating reader's size limits
(:mod:`reportgen.archive.check`), here without h5py so that what writes an archive can keep
to them before it runs (:mod:`reportgen.scene.budget`: a config's stored runs;
:func:`reportgen.scene.sweep.block_fits`: a sweep's saved blocks).  Limits that agree: a
config the budget takes writes an archive the reader takes."""

#: elements of one dataset (4e7: a run of the largest ``samples`` (2e6) with 20 columns)
MAX_DATASET_ELEMENTS = 40_000_000
#: elements of all datasets together
MAX_TOTAL_ELEMENTS = 100_000_000
#: bytes of one dataset as read (elements × item size: a fixed-width text of 40,000 bytes
#: per element made 90,000 elements, a few hundred bytes in the file, cost 3.6 GB to read)
MAX_DATASET_BYTES = 1 << 30
