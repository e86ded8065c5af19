"""Typed parameters: layering, validation and the one-line error messages."""

import pytest

from dustygas.config import Param, build_config, dump_toml, load_toml, parse_override
from dustygas.errors import ConfigError

SCHEMA = {
    "grid": {
        "nx": Param(64, "cells in x", min=1),
        "cfl": Param(0.4, "Courant number", min=0.0, max=1.0, min_open=True),
        "riemann": Param("hlle", "Riemann solver", choices=("hlle", "hllc")),
    },
    "particles": {"taus": Param([0.1], "stopping times", "1/Omega", min=0.0, min_open=True)},
}


def test_layering_defaults_file_overrides(tmp_path):
    f = tmp_path / "a.toml"
    f.write_text("[grid]\nnx = 32\ncfl = 0.8\n")
    cfg = build_config(SCHEMA, [f], ["grid.cfl=0.25", "particles.taus=[0.1, 1.0]"])
    assert cfg.grid.nx == 32
    assert cfg.grid.cfl == 0.25
    assert cfg.particles.taus == [0.1, 1.0]
    assert cfg["grid"]["riemann"] == "hlle"


def test_int_accepted_for_float_and_scalar_for_list():
    cfg = build_config(SCHEMA, overrides=["grid.cfl=1", "particles.taus=0.5"])
    assert cfg.grid.cfl == 1.0 and isinstance(cfg.grid.cfl, float)
    assert cfg.particles.taus == [0.5]


@pytest.mark.parametrize(
    "override, message",
    [
        ("grid.nxx=3", "unknown key 'grid.nxx'; did you mean 'grid.nx'?"),
        ("gird.nx=3", "unknown section 'gird'; did you mean 'grid'?"),
        ("grid.nx=abc", "grid.nx = 'abc': expected an integer"),
        ("grid.nx=2.5", "grid.nx = 2.5: expected an integer"),
        ("grid.nx=0", "grid.nx = 0 is out of range: allowed 1 <= value"),
        ("grid.cfl=0", "grid.cfl = 0.0 is out of range: allowed 0 < value <= 1"),
        ("grid.cfl=true", "grid.cfl = True: expected a number"),
        ("grid.riemann=roe", "grid.riemann = 'roe' is not allowed: choose one of hlle, hllc"),
        ("particles.taus=[0.1, -1]", "particles.taus = -1.0 is out of range"),
        ("grid.nx", "expected section.key=value"),
    ],
)
def test_bad_values_give_one_line_errors(override, message):
    with pytest.raises(ConfigError) as err:
        build_config(SCHEMA, overrides=[override])
    text = str(err.value)
    assert message in text
    assert "\n" not in text


def test_malformed_toml_names_file_and_line(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text("[grid]\nnx = = 3\n")
    with pytest.raises(ConfigError) as err:
        load_toml(f)
    assert "bad.toml: invalid TOML" in str(err.value) and "line 2" in str(err.value)


def test_parse_override_types():
    assert parse_override("a.b=1e-3") == ("a", "b", 1e-3)
    assert parse_override("a.b=true") == ("a", "b", True)
    assert parse_override("a.b=hllc") == ("a", "b", "hllc")


def test_dump_toml_round_trips_floats_bit_identically(tmp_path):
    values = {"grid": {"nx": 7, "cfl": 0.1 + 0.2, "riemann": 'x"y'}, "particles": {"taus": [1 / 3, 2e-300]}}
    f = tmp_path / "c.toml"
    f.write_text(dump_toml(values, top={"problem": "p"}))
    back = load_toml(f)
    assert back["problem"] == "p"
    assert back["grid"] == values["grid"]
    assert back["particles"]["taus"] == values["particles"]["taus"]
