"""cgs constants and the G = 1 disk code units."""

import math

from dustygas import units


def test_constants_match_published_values():
    """CODATA 2018: G = 6.67430e-8 cgs, k_B = 1.380649e-16 erg/K (exact); IAU: au = 1.495978707e13 cm
    (exact), nominal M_sun = G M_sun / G = 1.3271244e26 / 6.6743e-8 g = 1.98841e33 g."""
    assert math.isclose(units.G, 6.6743e-8, rel_tol=1e-12)
    assert math.isclose(units.k_B, 1.380649e-16, rel_tol=1e-15)
    assert math.isclose(units.au, 1.495978707e13, rel_tol=1e-15)
    assert math.isclose(units.M_sun, 1.3271244e26 / 6.6743e-8, rel_tol=1e-7)
    assert math.isclose(units.yr, 365.25 * 86400, rel_tol=1e-15)
    assert math.isclose(units.m_H, 1.6737e-24, rel_tol=1e-4)
    assert units.sigma_H2 == 2e-15 and units.MEAN_MOLECULAR_WEIGHT == 2.34


def test_disk_code_units():
    """G = 1 in (au, M_sun, sqrt(au^3/(G M_sun))); the time unit is yr/(2 pi) to 2e-5."""
    u = units.DISK_UNITS
    assert math.isclose(u.G, 1.0, rel_tol=1e-14)
    assert abs(u.time * 2 * math.pi / units.yr - 1) < 2e-5
    assert math.isclose(u.velocity, units.au / u.time, rel_tol=1e-15)
    assert math.isclose(u.velocity, 2.9785e6, rel_tol=1e-4)  # v_K at 1 au
    assert math.isclose(u.surface_density * u.length**2, units.M_sun, rel_tol=1e-15)
    assert math.isclose(u.density * u.length**3, units.M_sun, rel_tol=1e-15)
