"""Unit tests: the three recipes of docs/contributing.md, followed step by step.

Each test adds a tiny model exactly as its recipe says — a soil model, a force model, a design
check — registers it in its registry, runs it by name through a solver or the check runner and
checks the result against a hand calculation or the built-in model it reduces to. A model
with a kernel of its own also adds a module, a model id and a dispatch branch (recipe steps
1–2); these tiny models reuse an existing kernel (the recipes' shortcut), so the tests need no
source edit.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import pytest

from onbottom import Pipe, Sand
from onbottom.checks import registry as check_registry
from onbottom.checks.design import CheckOptions, CheckRow, run_checks
from onbottom.checks.registry import DesignCheck, register_check
from onbottom.dynamics.programmes import from_arrays
from onbottom.dynamics.section import simulate_section
from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
from onbottom.hydro import registry as force_registry
from onbottom.hydro.force_model import FORCE_MODEL_MORISON_LIFT, MorisonLift
from onbottom.hydro.registry import build_force_model, register_force_model
from onbottom.hydro.storm_kinematics import storm_kinematics
from onbottom.inputs.environment import Environment, LoadCombination
from onbottom.inputs.storm import Current, SeaState, Storm
from onbottom.soil import registry as soil_registry
from onbottom.soil.base import N_COMMON_STATE, LateralResistanceModel
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.registry import build_soil_model, register_soil_model

PIPE = Pipe(outer_diameter=0.4, submerged_weight=1500.0)
SAND = Sand(submerged_unit_weight=10.0e3, friction_coefficient=0.6)


# ---- recipe "Add a soil model" ----------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class FrictionAngle(LateralResistanceModel):
    """Coulomb friction given by an interface friction angle: μ = tan δ (tiny recipe model).

    Parameters
    ----------
    friction_angle_deg : float
        Interface friction angle δ [deg], in (0, 60).
    mobilisation_displacement : float
        Displacement at which μV is mobilised [m], > 0.
    """

    name: ClassVar[str] = "friction_angle"
    reference: ClassVar[str] = "Coulomb friction, μ = tan δ (recipe example)"
    state_size: ClassVar[int] = N_COMMON_STATE
    model_id: ClassVar[int] = CoulombFriction.model_id  # step 2 shortcut: the Coulomb kernel

    friction_angle_deg: float
    mobilisation_displacement: float = 1.0e-3

    def __post_init__(self) -> None:
        from onbottom._validate import in_range, positive

        in_range("FrictionAngle.friction_angle_deg", self.friction_angle_deg, 0.0, 60.0)
        positive("FrictionAngle.mobilisation_displacement", self.mobilisation_displacement)

    def _coulomb(self) -> CoulombFriction:
        mu = math.tan(math.radians(self.friction_angle_deg))
        return CoulombFriction(
            friction_coefficient=mu, mobilisation_displacement=self.mobilisation_displacement
        )

    @property
    def kernel(self):
        return self._coulomb().kernel

    @property
    def python_kernel(self):
        return self._coulomb().python_kernel

    def packed_parameters(self) -> np.ndarray:
        return self._coulomb().packed_parameters()

    def initial_state(self) -> np.ndarray:
        return np.zeros(self.state_size)

    def parameters(self) -> Mapping[str, Any]:
        return {
            "friction_angle_deg": self.friction_angle_deg,
            "mobilisation_displacement": self.mobilisation_displacement,
        }


@pytest.fixture
def clean_registries():
    registries = (soil_registry.SOIL_MODELS, check_registry.CHECKS, force_registry.FORCE_REGISTRY)
    saved = [reg.snapshot() for reg in registries]
    yield
    for reg, entries in zip(registries, saved, strict=True):
        reg.restore(entries)


def test_recipe_soil_model(clean_registries):
    register_soil_model(
        "friction_angle",
        FrictionAngle,
        lambda pipe, seabed, **options: FrictionAngle(**options),
        description="Coulomb friction from an interface friction angle",
    )
    soil = build_soil_model("friction_angle", PIPE, SAND, friction_angle_deg=30.0)
    assert isinstance(soil, FrictionAngle)
    # a ramp of H past μV = tan 30° · V: slides once H exceeds μV
    v = 1500.0
    t = np.linspace(0.0, 10.0, 101)
    prog = from_arrays(t, 0.1 * v * t, np.full_like(t, v), name="ramp")
    res = simulate_section(prog, soil, mass=200.0)
    twin = simulate_section(
        prog, CoulombFriction(friction_coefficient=math.tan(math.pi / 6)), mass=200.0
    )
    assert (
        res.success and json.loads(res.data.attrs["parameters"])["soil_model"] == "friction_angle"
    )
    np.testing.assert_array_equal(res.data["y"].values, twin.data["y"].values)
    f_soil = res.data["F_soil"].values
    assert np.max(np.abs(f_soil)) == pytest.approx(math.tan(math.pi / 6) * v, rel=1e-9)


# ---- recipe "Add a force model" ---------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class DragOnly:
    """Morison drag alone, F_Y = ½ρD C_D |U + V − ẏ|(U + V − ẏ), no inertia or lift (tiny
    recipe model on the Morison kernel).

    Parameters
    ----------
    cd : float
        Drag coefficient C_D [-], in [0, 10].
    added_mass : float
        C_a [-] of the pipe's added mass, >= 0 (default 2.29, a cylinder on a plane wall).
    """

    cd: float = 0.7
    added_mass: float = 2.29
    name: str = "drag_only"
    model_id: int = FORCE_MODEL_MORISON_LIFT  # step 2 shortcut: the Morison kernel

    @property
    def added_mass_coefficient(self) -> float:
        return self.added_mass

    def parameter_table(self, keulegan_carpenter, current_ratio) -> np.ndarray:
        rows = np.zeros((np.size(keulegan_carpenter), 4))  # P_CD, P_CM, P_CL, P_LIFT_REL
        rows[:, 0] = self.cd
        return rows

    def describe(self) -> dict[str, Any]:
        return {"force_model": self.name, "cd": self.cd, "source": "recipe example"}


def test_recipe_force_model(clean_registries):
    register_force_model("drag_only", DragOnly)
    fm = build_force_model("drag_only", {"cd": 0.9})
    assert isinstance(fm, DragOnly) and fm.cd == 0.9
    storm = Storm.standard(SeaState(hs=3.0, tp=9.0), build_up_hours=0.0, peak_hours=0.05)
    kin = storm_kinematics(storm, 13.0, diameter=0.4, current=Current(velocity=0.3, z0=5.2e-6))
    soil = CoulombFriction(friction_coefficient=0.6)
    settings = StormSolverSettings(record_interval=1.0)
    res = simulate_storm_section(PIPE, soil, kin, force_model=fm, settings=settings)
    ref = MorisonLift(cd=0.9, cm=0.0, cl=0.0, added_mass=2.29)
    twin = simulate_storm_section(PIPE, soil, kin, force_model=ref, settings=settings)
    assert res.success and res.data.attrs["force_model"] == "drag_only"
    np.testing.assert_array_equal(res.data["y"].values, twin.data["y"].values)
    assert np.all(res.data["F_Z"].values == 0.0)  # no lift


# ---- recipe "Add a design check" --------------------------------------------------------------
def minimum_weight_rows(props: Any, options: CheckOptions, condition: str) -> list[CheckRow]:
    """Project rule: submerged weight w_s >= 1000 N/m in every condition (recipe example)."""
    w = float(props.submerged_weight)
    u = 1000.0 / w if w > 0.0 else math.inf
    return [CheckRow("minimum_weight", condition, condition, u, u <= 1.0, {"w_s": w})]


def test_recipe_design_check(clean_registries):
    register_check(
        DesignCheck(
            "minimum_weight",
            "condition",
            minimum_weight_rows,
            ("minimum_weight",),
            "project rule (recipe example)",
        )
    )
    env = Environment(water_depth=20.0)
    combo = LoadCombination(
        name="c1", sea_state=SeaState(hs=3.0, tp=9.0), current=Current(velocity=0.3)
    )
    options = CheckOptions(checks=("vertical", "absolute", "minimum_weight"))
    rows = run_checks(PIPE, SAND, env, [combo], options)
    names = [r.name for r in rows]
    assert names == [
        "vertical_stability",
        "absolute_lateral",
        "absolute_vertical",
        "minimum_weight",
    ]
    row = rows[-1]
    assert row.utilisation == pytest.approx(1000.0 / 1500.0) and row.passes
