"""Physical constants in cgs as plain floats, and the code units of the global-disk engines.

Constants are taken from :mod:`astropy.constants` / :mod:`astropy.units` once, at import
(CODATA 2018 and IAU 2015 in astropy >= 4), and stored as ``float`` so that kernels and
formulas never touch astropy objects. Use astropy only at the edges (set-up, input, output);
:func:`to_cgs` turns an astropy ``Quantity`` into a cgs float there.

Constants (cgs)
---------------
``G``        gravitational constant [cm^3 g^-1 s^-2]
``M_sun``    nominal solar mass [g] (IAU 2015 B3, via astropy)
``au``       astronomical unit [cm] (IAU 2012 B2, exact)
``yr``       Julian year, 365.25 d [s]
``k_B``      Boltzmann constant [erg K^-1]
``m_p``      proton mass [g]
``m_H``      mass of a hydrogen atom [g], the standard atomic weight 1.00794 u
``sigma_H2`` geometric collision cross-section of molecular hydrogen, 2e-15 cm^2
             (the value used by Weidenschilling 1977 and Birnstiel, Dullemond & Brauer
             2010, A&A 513, A79; it sets the gas mean free path
             :math:`\\lambda = \\mu m_H/(\\rho_g \\sigma_{H_2})`)
``MEAN_MOLECULAR_WEIGHT``
             2.34, the mean molecular weight of a solar-composition molecular gas
             (H2 + He; Hayashi 1981; Armitage 2013, *Astrophysics of Planet Formation*);
             the default wherever a sound speed or mean free path needs :math:`\\mu`.

Code units of the global-disk (SPH) engine
------------------------------------------
Length 1 au, mass 1 M_sun, and time :math:`\\sqrt{\\mathrm{au}^3/(G M_\\odot)}` so that
:math:`G = 1`; a circular orbit at 1 au around 1 M_sun then has :math:`\\Omega = 1` and period
:math:`2\\pi`, so the time unit is one year divided by :math:`2\\pi` (to 2e-5: the Julian year
differs slightly from the Keplerian period at 1 au). See :data:`DISK_UNITS`.

>>> round(DISK_UNITS.G, 12)
1.0
>>> round(DISK_UNITS.time * 2 * 3.141592653589793 / yr, 4)
1.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from astropy import constants as _const
from astropy import units as _u

__all__ = [
    "G",
    "M_sun",
    "au",
    "yr",
    "k_B",
    "m_p",
    "m_H",
    "sigma_H2",
    "MEAN_MOLECULAR_WEIGHT",
    "CodeUnits",
    "DISK_UNITS",
    "to_cgs",
]

G: float = float(_const.G.cgs.value)
M_sun: float = float(_const.M_sun.cgs.value)
au: float = float(_u.au.to(_u.cm))
yr: float = float(_u.yr.to(_u.s))
k_B: float = float(_const.k_B.cgs.value)
m_p: float = float(_const.m_p.cgs.value)
m_H: float = float((1.00794 * _u.u).to(_u.g).value)
sigma_H2: float = 2.0e-15
MEAN_MOLECULAR_WEIGHT: float = 2.34


@dataclass(frozen=True)
class CodeUnits:
    """A system of code units given by its length, mass and time units in cgs.

    Multiply a code value by the matching attribute to get cgs; divide a cgs value by it to
    get code units (``r_code = r_cm / units.length``).
    """

    length: float
    mass: float
    time: float

    @property
    def velocity(self) -> float:
        """cm/s per code velocity unit."""
        return self.length / self.time

    @property
    def acceleration(self) -> float:
        return self.length / self.time**2

    @property
    def density(self) -> float:
        """g/cm^3 per code density unit."""
        return self.mass / self.length**3

    @property
    def surface_density(self) -> float:
        """g/cm^2 per code surface-density unit."""
        return self.mass / self.length**2

    @property
    def G(self) -> float:
        """The gravitational constant in these units (1 for :data:`DISK_UNITS`)."""
        return G * self.mass * self.time**2 / self.length**3


#: au, M_sun and yr/(2 pi) (precisely sqrt(au^3/(G M_sun))), so that G = 1.
DISK_UNITS = CodeUnits(length=au, mass=M_sun, time=math.sqrt(au**3 / (G * M_sun)))


def to_cgs(quantity) -> float | object:
    """Value of an astropy ``Quantity`` in cgs (a float, or an array for array quantities).

    >>> to_cgs(1 * _u.km / _u.s)
    100000.0
    """
    value = quantity.cgs.value
    return float(value) if getattr(value, "ndim", 0) == 0 else value
