"""The Magic Formula keeps xarray's named dimensions, as the laws do."""

from __future__ import annotations

import numpy as np
import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.tyre.mf.model import MagicFormula

xr = pytest.importorskip("xarray")


@pytest.fixture(scope="module")
def mf() -> MagicFormula:
    return MagicFormula.from_file("MagicFormula62")


def _kappa():
    values = np.linspace(-0.3, 0.3, 7)
    return xr.DataArray(values, dims="kappa", coords={"kappa": values})


def _loads():
    values = np.array([2000.0, 4000.0, 6000.0])
    return xr.DataArray(values, dims="load", coords={"load": values, "label": ("load",
                                                     ["light", "nominal", "heavy"])})


def test_pure_forces_broadcast_over_named_dims(mf):
    kappa, fz = _kappa(), _loads()
    out = mf.fx0(kappa, fz)
    assert isinstance(out, xr.DataArray)
    assert out.dims == ("kappa", "load") and out.shape == (7, 3)
    assert out.name == "F_x0" and out.attrs["units"] == "N"
    assert list(out["label"].values) == ["light", "nominal", "heavy"]
    np.testing.assert_array_equal(out["kappa"].values, kappa.values)
    plain = mf.fx0(kappa.values[:, None], fz.values[None, :])
    np.testing.assert_array_equal(out.values, plain)
    alpha = xr.DataArray(np.radians([[1.0, 2.0], [4.0, 8.0]]), dims=("run", "step"))
    fy = mf.fy0(alpha, 4000.0, gamma=0.01)
    assert fy.dims == ("run", "step") and fy.attrs["units"] == "N"
    np.testing.assert_array_equal(fy.values, mf.fy0(alpha.values, 4000.0, gamma=0.01))


def test_a_shared_dimension_pairs_values_instead_of_crossing_them(mf):
    run = {"run": [10, 11, 12]}
    kappa = xr.DataArray([0.02, 0.05, 0.1], dims="run", coords=run)
    fz = xr.DataArray([3000.0, 4000.0, 5000.0], dims="run", coords=run)
    out = mf.fx0(kappa, fz)
    assert out.dims == ("run",) and list(out["run"].values) == [10, 11, 12]
    np.testing.assert_array_equal(out.values, mf.fx0(kappa.values, fz.values))


def test_combined_slip_and_weights_keep_dims(mf):
    kappa, fz = _kappa(), _loads()
    alpha = xr.DataArray(np.radians([0.0, 3.0, 6.0]), dims="alpha")
    fx = mf.fx(kappa, alpha, fz)
    fy = mf.fy(kappa, alpha, fz)
    for out, name in ((fx, "F_x"), (fy, "F_y")):
        assert set(out.dims) == {"kappa", "alpha", "load"} and out.name == name
        assert out.attrs["units"] == "N"
    k3 = fx.transpose("kappa", "alpha", "load")
    plain = mf.fx(kappa.values[:, None, None], alpha.values[None, :, None],
                  fz.values[None, None, :])
    np.testing.assert_array_equal(k3.values, plain)
    np.testing.assert_array_equal(fx.isel(alpha=0).transpose("kappa", "load").values,
                                  mf.fx0(kappa, fz).values)  # G_xa = 1 at alpha = 0
    G, S = mf.weight_y(kappa, alpha, fz)
    assert G.name == "G_yk" and G.attrs["units"] == "1"
    assert S.name == "S_Vyk" and S.attrs["units"] == "N"
    assert set(G.dims) == set(S.dims) == {"kappa", "alpha", "load"}
    assert mf.weight_x(kappa, alpha, 4000.0).attrs["long_name"].startswith("combined")


def test_load_functions_keep_dims(mf):
    fz = _loads()
    for method, unit in (("mu_x_peak", "1"), ("mu_y_peak", "1"), ("slip_stiffness", "N"),
                         ("cornering_stiffness", "N/rad")):
        out = getattr(mf, method)(fz)
        assert out.dims == ("load",) and out.attrs["units"] == unit, method
        np.testing.assert_array_equal(out.values, getattr(mf, method)(fz.values))


def test_plain_numbers_still_give_plain_numbers(mf):
    assert isinstance(mf.fx0(0.1, 4000.0), float)
    assert isinstance(mf.fx0(np.array([0.1, 0.2]), 4000.0), np.ndarray)


def test_labelled_inputs_are_checked_like_arrays(mf):
    with pytest.raises(InputError, match="fz must hold positive finite loads"):
        mf.fx0(_kappa(), xr.DataArray([4000.0, -1.0], dims="load"))
    with pytest.raises(InputError, match="must be DataArrays too"):
        mf.fx0(_kappa(), np.array([3000.0, 4000.0]))
