"""Input and output: atomic files, HDF5 snapshots/checkpoints/history, run directories."""

from .atomic import atomic_path, atomic_write_text
from .hdf5 import read_h5, write_h5
from .rundir import RunDirectory

__all__ = ["atomic_path", "atomic_write_text", "read_h5", "write_h5", "RunDirectory"]
