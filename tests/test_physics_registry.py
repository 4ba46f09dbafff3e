"""A physics family registered in one place reaches every part that knows of physics.

A small family defined here, with no other file touched, becomes a keyword of
``Simulation``, a key of a configuration's ``[model]`` table, part of a checkpoint and
part of a GSD frame's log; and the built-in families keep their keywords.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import pytest

import edmd2d as ed
from edmd2d import checkpoint, config, physics
from edmd2d._validate import as_positive_float


@dataclass(frozen=True)
class Label(physics.Family):
    """A made-up family: one number per simulation, which the engine never reads."""

    name: ClassVar[str] = "label"
    keywords: ClassVar[tuple] = (
        physics.Keyword("label_level", None, "duration", "a number >= 0 to carry along"),
    )

    label_level: float

    @classmethod
    def check(cls, system=None, *, label_level=None):
        if label_level is None:
            return None
        with physics.about("label_level"):
            return cls(as_positive_float("label_level", label_level, allow_zero=True))


@pytest.fixture
def label():
    physics.register(Label)
    try:
        yield Label
    finally:
        physics.unregister("label")


def gas(**kwargs):
    return ed.make_gas(40, 0.3, seed=3, **kwargs)


def test_a_registered_family_is_a_keyword_of_simulation(label):
    sim = gas(label_level=2.5)
    assert sim.families == {"label": Label(2.5)}
    assert gas().families == {}
    with pytest.raises(ValueError, match="label_level must be >= 0"):
        gas(label_level=-1.0)
    with pytest.raises(TypeError, match="did you mean 'label_level'"):
        gas(label_levle=1.0)


def test_an_unregistered_keyword_is_refused():
    with pytest.raises(TypeError, match="unexpected keyword argument 'label_level'"):
        gas(label_level=1.0)
    with pytest.raises(TypeError, match="did you mean 'restitution'"):
        gas(restitutoin=0.9)


def test_a_registered_family_is_a_key_of_the_configuration(label):
    text = ("[gas]\nn = 40\npacking_fraction = 0.3\n[model]\nseed = 1\n"
            "label_level = 4.0\n[run]\nduration = 1\n")
    cfg = config.loads(text)
    assert cfg.data["model"]["label_level"] == 4.0
    sim, _ = config.build(cfg, 1)
    assert sim.families["label"].label_level == 4.0
    with pytest.raises(config.ConfigError, match=r"line 6: model.label_level"):
        config.loads(text.replace("4.0", "-4.0"))


def test_without_registration_the_key_is_unknown():
    text = ("[gas]\nn = 40\npacking_fraction = 0.3\n[model]\nlabel_level = 4.0\n"
            "[run]\nduration = 1\n")
    with pytest.raises(config.ConfigError, match="model.label_level: unknown key"):
        config.loads(text)


def test_a_registered_family_survives_a_checkpoint(label, tmp_path):
    sim = gas(label_level=1.5).advance(until=1.0)
    checkpoint.save(sim, tmp_path / "c.edmd2d")
    back = checkpoint.load(tmp_path / "c.edmd2d")
    assert back.families == {"label": Label(1.5)}
    assert back.advance(until=2.0).positions.tolist() == sim.advance(until=2.0).positions.tolist()
    physics.unregister("label")
    try:
        with pytest.raises(ValueError, match="physics family 'label', which is not registered"):
            checkpoint.load(tmp_path / "c.edmd2d")
    finally:
        physics.register(Label)


def test_a_registered_family_is_in_the_gsd_log(label, tmp_path):
    gsd_hoomd = pytest.importorskip("gsd.hoomd")
    from edmd2d.io import gsd as edmd2d_gsd

    path = tmp_path / "t.gsd"
    with edmd2d_gsd.Writer(path) as out:
        out.write(gas(label_level=0.75))
    with gsd_hoomd.open(str(path), "r") as f:
        assert f[0].log["edmd2d/label/label_level"].tolist() == [0.75]
    assert edmd2d_gsd.read(path).families == {"label": Label(0.75)}


def test_the_registry_refuses_a_taken_name_or_keyword(label):
    with pytest.raises(ValueError, match="name of its own"):
        physics.register(Label)

    @dataclass(frozen=True)
    class Clash(physics.Family):
        name: ClassVar[str] = "clash"
        keywords: ClassVar[tuple] = (physics.Keyword("tc", None, "duration", "taken"),)

    with pytest.raises(ValueError, match="keyword 'tc' of the family 'clash' is taken"):
        physics.register(Clash)
    with pytest.raises(TypeError, match="subclass of edmd2d.physics.Family"):
        physics.register(dict)
    assert "clash" not in physics.FAMILIES


def test_the_built_in_families_and_their_keywords():
    assert list(physics.FAMILIES) == ["restitution", "gravity", "heated_walls",
                                      "thermostat", "growth", "resting", "shear", "rough",
                                      "moving_walls"]
    assert [kw for kw in physics.KEYWORDS] == ["restitution", "wall_restitution", "tc",
                                               "gravity", "wall_temperatures",
                                               "thermostat", "growth", "resting",
                                               "rest_height", "shear_rate", "shear_offset",
                                               "tangential_restitution", "friction",
                                               "wall_tangential_restitution",
                                               "wall_friction", "inertia",
                                               "angular_velocities", "angles",
                                               "wall_motions"]
    assert not physics.Resting.built_in  # (a family of the registry, checked always)
    assert physics.Resting.always
    for name in ("restitution", "wall_restitution", "tc", "gravity", "thermostat",
                 "resting", "rest_height", "shear_rate", "tangential_restitution"):
        assert name in config._schema._model_schema()
    assert "growth" not in config._schema._model_schema()  # (compression is not a config run)
    assert "wall_motions" not in config._schema._model_schema()  # (from [[walls]] tables)
