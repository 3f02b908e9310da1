"""Calibrations: fits from a DataFrame, their values, standard errors and residuals."""

from __future__ import annotations

import uuid

import pandas as pd
import pytest

import tribosim

from conftest import REPO

TABLE3_HARDNESS = REPO / "docs" / "calibration" / "table3_hardness.csv"
TABLE3_WEAR = REPO / "docs" / "calibration" / "table3_wear.csv"
#: docs/calibration.md prints the hardness fit to two decimals: half a unit of the last.
PRINTED = 0.005


def test_hardness_from_a_dataframe(client: tribosim.Client) -> None:
    table = pd.read_csv(TABLE3_HARDNESS, comment="#")
    fit = client.calibrations.fit("hardness", table)
    assert fit.kind == "hardness"
    # docs/calibration.md, "Hardness law": 2454.99 +- 26.98 and 63.38 +- 4.96 MPa.
    a, b = fit.values["a_mpa"], fit.values["b_mpa"]
    assert (a.value, a.standard_error) == pytest.approx((2454.99, 26.98), abs=PRINTED)
    assert (b.value, b.standard_error) == pytest.approx((63.38, 4.96), abs=PRINTED)
    assert list(fit.estimates.index) == ["a_mpa", "b_mpa"]
    assert fit.estimates.loc["a_mpa", "value"] == a.value

    residuals = fit.residuals
    assert list(residuals.columns) == ["cycles", "fitted_mpa", "hardness_mpa", "residual_mpa"]
    # The scene's bulk hardness is a point at n = 1 besides the table's five.
    assert residuals["cycles"].tolist() == [1] + table["cycles"].tolist()
    difference = residuals["hardness_mpa"] - residuals["fitted_mpa"]
    assert difference.tolist() == pytest.approx(residuals["residual_mpa"].tolist(), abs=1e-9)
    assert fit.scene["disc"]["hardness_table"] == table.values.tolist()


def test_options(client: tribosim.Client) -> None:
    table = pd.read_csv(TABLE3_HARDNESS, comment="#")
    fit = client.calibrations.fit("hardness", table, include_bulk=False)
    # docs/calibration.md: without the bulk value, 2427.65 +- 45.05 MPa.
    a = fit.values["a_mpa"]
    assert (a.value, a.standard_error) == pytest.approx((2427.65, 45.05), abs=PRINTED)
    assert len(fit.residuals) == len(table)


def test_submit_then_get(client: tribosim.Client) -> None:
    calibration = client.calibrations.submit("hardness", TABLE3_HARDNESS.read_text())
    assert calibration.info.kind == "hardness"
    fit = calibration.wait()
    again = client.calibrations.get(calibration.id)
    assert again.info.status == "succeeded"
    assert again.info.result == fit.raw


def test_two_regimes(client: tribosim.Client) -> None:
    fit = client.calibrations.fit(
        "archard", TABLE3_WEAR, scene={"numerics": {"grid": 16}}, regime_change=300
    )
    assert {
        "one_regime.archard_k",
        "two_regimes.archard_k_before",
        "two_regimes.archard_k_after",
    } <= set(fit.values)
    assert len(fit.residuals) == 5
    assert fit.scene["numerics"]["grid"] == 16


def test_a_bad_table_names_it(client: tribosim.Client) -> None:
    with pytest.raises(tribosim.ValidationError) as refused:
        client.calibrations.submit("hardness", {"cycles": [10, 60], "hardness_mpa": [2551, -1]})
    assert [f.path for f in refused.value.fields] == ["table"]
    assert "hardness_mpa" in refused.value.fields[0].message


def test_an_option_of_another_fit_is_refused(client: tribosim.Client) -> None:
    with pytest.raises(tribosim.ValidationError) as refused:
        client.calibrations.submit("hardness", TABLE3_HARDNESS.read_text(), e_corr_v=-0.1)
    assert [f.path for f in refused.value.fields] == ["options.e_corr_v"]


def test_a_fit_that_fails_raises(client: tribosim.Client) -> None:
    # A last point far below the others: the best k lies beyond the search's bracket
    # (a decade either side of eq. 14's k from that point), so the fit does not converge.
    table = "time_s,volume_mm3\n10,0.1\n60,0.2\n100,0.0002\n"
    calibration = client.calibrations.submit("archard", table, scene={"numerics": {"grid": 16}})
    with pytest.raises(tribosim.RunFailedError, match="edge of the bracket") as failed:
        calibration.wait()
    assert failed.value.record.status == "failed"


def test_an_unknown_calibration(client: tribosim.Client) -> None:
    with pytest.raises(tribosim.NotFoundError):
        client.calibrations.get(str(uuid.uuid4()))


def test_a_running_fit_is_listed_cancelled_and_deleted(client: tribosim.Client) -> None:
    every_cycle = {"preset": "dalmau2018-316l", "overrides": {"numerics": {"cycle_step": 1}}}
    calibration = client.calibrations.submit("archard", TABLE3_WEAR, every_cycle)
    assert calibration.id in [c.id for c in client.calibrations.list(kind="archard")]
    assert calibration.cancel().status == "cancelled"
    listed = client.calibrations.list(status="cancelled")
    assert calibration.id in [c.id for c in listed]
    calibration.delete()
    with pytest.raises(tribosim.NotFoundError):
        calibration.refresh()


def test_the_tafel_domain_is_an_option(client: tribosim.Client) -> None:
    # Table 2's line, E_corr -0.10 V, 1 to 1000 mV below it, no noise.
    etas = [-1e-3 * k for k in range(1, 1001)]
    table = {
        "potential_v": [-0.10 + eta for eta in etas],
        "current_density_a_cm2": [-(10 ** ((-3.31 - eta) / 0.56)) for eta in etas],
    }
    fit = client.calibrations.fit(
        "tafel",
        table,
        e_corr_v=-0.10,
        tafel_overpotential_max_v=-0.2,
        tafel_overpotential_min_v=-0.8,
    )
    # 200 to 800 mV below E_corr, 1 mV apart, both ends included.
    assert fit.raw["domain"]["points"] == 601
    assert fit.raw["domain"]["given"] is True
    with pytest.raises(tribosim.ValidationError) as refused:
        client.calibrations.submit("tafel", table, e_corr_v=-0.10, tafel_overpotential_max_v=-150)
    assert [f.path for f in refused.value.fields] == ["options.tafel_overpotential_max_v"]
