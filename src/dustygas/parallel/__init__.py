"""Domain decomposition over MPI ranks: blocks of the mesh, halo exchange, a rank-aware engine.

The serial path never imports this package's MPI parts: :func:`launched_under_mpi` reads the
process environment only, and :mod:`mpi4py` is imported the first time a communicator is
needed.

* :mod:`.decomposition` -- the Cartesian rank layout (which axes are split, into how many
  blocks), each block's offset and a :class:`~.decomposition.BlockMesh` whose cell centres are
  those of the whole mesh (bit for bit);
* :mod:`.halo` -- the one halo exchange: ghost layers from the neighbouring blocks, periodic
  images included, axis by axis in the order of the serial ghost fill;
* :mod:`.gas` -- :class:`~.gas.DistributedGridEngine`, the grid engine on one block with the
  run-loop protocol of the whole box (gathered diagnostics and outputs on rank 0);
* :mod:`.particles` -- :class:`~.particles.BlockParticleEngine`, the particle–gas engine on one
  block of a z split: migration, halo particles, field halos;
* :mod:`.coupled` -- :class:`~.coupled.DistributedParticleEngine`, the particle–gas run over
  the ranks (z cuts balancing cells and particles, outputs gathered in the serial order).
"""

from .comm import launched_under_mpi, rank_and_size
from .decomposition import BlockMesh, Decomposition, choose_layout

__all__ = ["launched_under_mpi", "rank_and_size", "Decomposition", "BlockMesh", "choose_layout"]
