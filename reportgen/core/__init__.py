"""Pure numerics on ndarrays: models, integrators, exact references.

Nothing here does I/O, plotting or HDF5.
"""
