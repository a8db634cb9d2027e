"""``Dataset.from_frame`` and ``Dataset.to_frame``: pandas in and out, units in the names."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.io import Dataset, list_datasets, load_dataset


def _full() -> Dataset:
    """A dataset with every canonical column, loaded from display units."""
    frame = pd.DataFrame({
        "mu": [0.8, 0.7, 0.65], "p [MPa]": [0.1, 0.2, 0.4], "v [mm/s]": [1.0, 10.0, 100.0],
        "T [degC]": [20.0, 40.0, 60.0], "F_N [N]": [10.0, 20.0, 40.0], "s [%]": [5, 10, 20],
        "mu_std": [0.01, 0.02, 0.015], "n": [3, 4, 5], "surface": ["steel", "steel", "ice"]})
    return load_dataset(frame)


def test_to_frame_names_si_units_and_round_trips():
    ds = _full()
    frame = ds.to_frame()
    assert list(frame.columns) == ["mu", "p [Pa]", "v [m/s]", "T [K]", "F_N [N]", "s",
                                   "mu_std", "n", "surface"]
    np.testing.assert_allclose(frame["p [Pa]"], [1e5, 2e5, 4e5])
    np.testing.assert_allclose(frame["v [m/s]"], [1e-3, 1e-2, 1e-1])
    np.testing.assert_allclose(frame["T [K]"], [293.15, 313.15, 333.15])
    np.testing.assert_allclose(frame["s"], [0.05, 0.1, 0.2])
    assert frame.attrs["units"]["p"] == "Pa" and frame.attrs["name"] == ds.name
    back = Dataset.from_frame(frame, name="again")
    pd.testing.assert_frame_equal(back.frame, ds.frame)  # exact: SI in, SI out
    assert back.name == "again" and back.source == "<DataFrame>"
    frame.loc[0, "p [Pa]"] = -1.0  # a copy: the dataset is unchanged
    assert ds.frame.loc[0, "p"] == 1e5


def test_display_units_round_trip_like_the_csv():
    ds = _full()
    frame = ds.to_frame("display")
    assert "p [MPa]" in frame.columns and "T [degC]" in frame.columns
    np.testing.assert_allclose(frame["T [degC]"], [20.0, 40.0, 60.0])
    back = Dataset.from_frame(frame)
    pd.testing.assert_frame_equal(back.frame, ds.frame, check_exact=False, rtol=1e-12)


#: Packaged datasets laid out as printed in a source, with the options their notes give.
OPTIONS = {"thesis-steel-original": {"mapping": "mu=FC,p=CP,v=DV", "units": "p=MPa,v=m/s"}}


@pytest.mark.parametrize("name", [d["name"] for d in list_datasets()])
def test_every_packaged_dataset_round_trips(name):
    ds = load_dataset(name, **OPTIONS.get(name, {}))
    pd.testing.assert_frame_equal(Dataset.from_frame(ds.to_frame()).frame, ds.frame)


def test_from_frame_takes_mapping_units_and_area():
    frame = pd.DataFrame({"FC": [0.5, 0.4], "load": [10.0, 20.0], "speed": [1.0, 2.0]})
    ds = Dataset.from_frame(frame, mapping="mu=FC", units={"F_N": "N", "v": "m/s"},
                            area="100 mm^2")
    np.testing.assert_allclose(ds.frame["p"], [1e5, 2e5])
    assert ds.units["F_N"] == "N"


@pytest.mark.parametrize("column, values, match", [
    ("mu", [0.5, "x", 0.3], "non-numeric value 'x'"),
    ("mu", [0.5, -1.0, 0.3], "must be >= 0"),
    ("p [MPa]", [0.1, 0.2, np.inf], "not finite"),
    ("p [MPa]", [0.1, -0.2, 0.3], "contact pressure must be >= 0"),
])
def test_bad_values_name_column_and_row(column, values, match):
    frame = pd.DataFrame({"mu": [0.5, 0.4, 0.3], "p [MPa]": [0.1, 0.2, 0.3]})
    frame[column] = pd.Series(values, dtype=object)
    with pytest.raises(InputError, match=match) as info:
        Dataset.from_frame(frame)
    bad = next(i for i, v in enumerate(values) if v in ("x", -1.0, np.inf, -0.2))
    assert info.value.column == column
    assert f"row position {bad}" in str(info.value)


def test_from_frame_refuses_what_the_csv_loader_refuses():
    with pytest.raises(InputError, match="length|unit"):
        Dataset.from_frame(pd.DataFrame({"mu": [0.5], "p [furlong]": [1.0]}))
    with pytest.raises(InputError, match="mu"):
        Dataset.from_frame(pd.DataFrame({"p [MPa]": [0.1]}))
    with pytest.raises(InputError, match="no rows"):
        Dataset.from_frame(pd.DataFrame({"mu": [], "p [MPa]": []}))
    with pytest.raises(InputError, match="takes a pandas DataFrame"):
        Dataset.from_frame({"mu": [0.5]})  # type: ignore[arg-type]
    with pytest.raises(InputError, match="'si' or 'display'"):
        _full().to_frame("MPa")


def test_from_frame_matches_load_dataset_of_the_csv(tmp_path):
    ds = _full()
    path = ds.to_csv(tmp_path / "full.csv")
    from_file = load_dataset(path)
    from_frame = Dataset.from_frame(pd.read_csv(path, comment="#"))
    pd.testing.assert_frame_equal(from_frame.frame, from_file.frame)
