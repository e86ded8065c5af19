"""External forces: a point-mass star, vertical disk gravity and a constant field.

* star of mass :math:`M` at the origin with Plummer softening :math:`\\epsilon`:
  :math:`\\mathbf a = -GM\\,\\mathbf r/(r^2+\\epsilon^2)^{3/2}`, :math:`\\Phi = -GM/\\sqrt{r^2+\\epsilon^2}`;
  particles that come closer than the accretion radius are removed and their mass, momentum and
  angular momentum are added to the star's (:class:`~dustygas.sph.engine.SPHEngine` does that);
* vertical gravity of a thin disk at the midplane (shearing sheet, thesis §4.3):
  :math:`a_z = -\\Omega^2 z`, :math:`\\Phi = \\Omega^2 z^2/2`;
* a constant field :math:`\\mathbf g`: :math:`\\Phi = -\\mathbf g\\cdot\\mathbf r`.

All are central or uniform, so they conserve angular momentum about the origin (star, vertical
gravity about the z axis) or linear momentum perpendicular to :math:`\\mathbf g`.

Examples
--------
>>> import numpy as np
>>> ext = ExternalForces(star_gm=1.0)
>>> acc = np.zeros((1, 3)); phi = np.zeros(1)
>>> ext.add(np.array([[2.0, 0.0, 0.0]]), acc, phi)
>>> acc[0].tolist(), phi.tolist()
([-0.25, 0.0, 0.0], [-0.5])
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit, prange

__all__ = ["ExternalForces", "external_accelerations"]


@njit(parallel=True, cache=True)
def external_accelerations(pos, star_gm, softening, omega_z, gx, gy, gz, acc, phi):
    """Add external accelerations to ``acc`` and write the potential into ``phi``."""
    eps2 = softening * softening
    oz2 = omega_z * omega_z
    for a in prange(pos.shape[0]):
        x, y, z = pos[a, 0], pos[a, 1], pos[a, 2]
        p = -(gx * x + gy * y + gz * z)
        ax, ay, az = gx, gy, gz
        if star_gm != 0.0:
            r2 = x * x + y * y + z * z + eps2
            rinv = 1.0 / math.sqrt(r2)
            f = star_gm * rinv * rinv * rinv
            ax -= f * x
            ay -= f * y
            az -= f * z
            p -= star_gm * rinv
        if oz2 != 0.0:
            az -= oz2 * z
            p += 0.5 * oz2 * z * z
        acc[a, 0] += ax
        acc[a, 1] += ay
        acc[a, 2] += az
        phi[a] = p


@dataclass(frozen=True)
class ExternalForces:
    """External accelerations acting on every particle.

    Attributes
    ----------
    star_gm
        :math:`GM_\\star` of a star fixed at the origin (0: none).
    softening
        Plummer softening length :math:`\\epsilon` of the star's potential.
    accretion_radius
        Particles closer than this to the star are accreted (0: never).
    omega_z
        Vertical frequency :math:`\\Omega` of the disk gravity :math:`-\\Omega^2 z` (0: none).
    field
        Constant acceleration :math:`\\mathbf g` (three components).
    """

    star_gm: float = 0.0
    softening: float = 0.0
    accretion_radius: float = 0.0
    omega_z: float = 0.0
    field: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def active(self) -> bool:
        return bool(self.star_gm or self.omega_z or any(self.field))

    def add(self, pos: np.ndarray, acc: np.ndarray, phi: np.ndarray) -> None:
        """Add the accelerations to ``acc`` and store the potential in ``phi``."""
        gx, gy, gz = (float(v) for v in self.field)
        external_accelerations(pos, float(self.star_gm), float(self.softening), float(self.omega_z),
                               gx, gy, gz, acc, phi)

    def accreted(self, pos: np.ndarray) -> np.ndarray:
        """Indices of particles inside the accretion radius."""
        if self.star_gm == 0.0 or self.accretion_radius <= 0.0:
            return np.empty(0, dtype=np.int64)
        r2 = np.einsum("ij,ij->i", pos, pos)
        return np.flatnonzero(r2 < self.accretion_radius**2)
