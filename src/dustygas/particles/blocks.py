"""The hooks of the coupled step where a decomposed run does more than one block
(:class:`OneBlock`: what they do when the engine holds the whole box).

:class:`~dustygas.particles.coupling.ParticleGridEngine` calls them during a step;
:class:`dustygas.parallel.particles.BlockParticleEngine` overrides them with the exchanges
between blocks (halo particles, field halos, agreed rows).
"""

from __future__ import annotations

import numpy as np

from .boundaries import images_wrap
from .push import occupied_rows, padded_rows

__all__ = ["OneBlock"]


class OneBlock:
    """The hooks of one block holding the whole box (a mixin of the coupled engine)."""

    #: the engine holds the whole box (a block of a decomposed run: False)
    _whole_box = True

    def _wrap_images(self) -> bool:
        """Whether the deposits read the periodic images in place
        (:func:`~dustygas.particles.boundaries.images_wrap`); a decomposed run builds its records."""
        return images_wrap(self._pb, self._reach, self.geometry.shape)

    def _add_halo(self, m: int) -> int:
        """After the ``m`` image records of a sort: add the records of the neighbouring blocks'
        particles (:mod:`dustygas.parallel.particles`); returns the new count. One block: none."""
        return m

    def _occupied_rows(self, n: int, margin: int) -> tuple[int, int]:
        """Rows ``[k_lo, k_hi)`` of the whole mesh whose fields the particles need this step
        (:func:`~dustygas.particles.push.occupied_rows`)."""
        nx, ny, nz = self.geometry.shape
        return occupied_rows(self._keys, n, nx, ny, nz, margin, self._field_kinds[2] == 0)

    def _block_rows(self, rows: tuple[int, int]) -> tuple[int, int]:
        """The domain rows of this block among the rows ``rows`` of the whole mesh."""
        return rows

    def _padded_rows(self, rows: tuple[int, int], gz: int) -> tuple[int, int]:
        """The padded z rows of a field with ``gz`` ghost layers to fill and filter for the
        domain rows ``rows`` of the whole mesh (with the ghost rows beyond them where they reach a z face)."""
        return padded_rows(rows, gz, self.geometry.shape[2])

    def _field_halo(self, field: np.ndarray, gz: int) -> None:
        """Fill the z ghost rows of ``field`` that neighbouring blocks hold. One block: none."""

    def _kicked(self, n: int) -> None:
        """After the kick: the neighbouring blocks' halo particles get their drag deposits. One block: none."""
