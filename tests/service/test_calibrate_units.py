"""A measured column or key in another unit than the contract's (power_MW, te_N): the
calibration's CSV header (beltstudy calibrate) and body (POST /calibrations) name the column
to write and the conversion, not the name alone."""

from __future__ import annotations

import pytest

from beltstudy.engine import InputError
from beltstudy.service.calibration import read_calibration
from beltstudy.service.cli.calibrate import read_measured
from beltstudy.service.errors import Invalid


@pytest.mark.parametrize("header,needle", [
    ("load,temperature_c,power_MW", "unknown column 'power_MW'; did you mean 'power_kw'? "
                                    "(in kW: MW x 1000)"),
    ("load,temperature_c,te_N", "unknown column 'te_N'; did you mean 'te_kn'? (in kN: N / 1000)"),
    ("load,temperature_F,power_kw", "did you mean 'temperature_c'? (in degrees Celsius: "
                                    "(F - 32) / 1.8)"),
    # the unit in brackets, as a spreadsheet heads its columns: renamed as told without the
    # conversion, 50-86 F were read as Celsius
    ("load,temperature_c [F],power_kw", "unknown column 'temperature_c [F]'; did you mean "
                                        "'temperature_c'? (in degrees Celsius: (F - 32) / 1.8)"),
    ("load,temperature_c (degF),power_kw", "did you mean 'temperature_c'? (in degrees "
                                           "Celsius: (F - 32) / 1.8)"),
    ("load,temperature_c,power_kw [W]", "unknown column 'power_kw [W]'; did you mean "
                                        "'power_kw'? (in kW: W / 1000)"),
    ("load,temperature_c,power [kW]", "unknown column 'power [kW]'; did you mean 'power_kw'? "
                                      "(its unit, kW, is in the name)"),
    ("load,temperature [K],power_kw", "did you mean 'temperature_c'? (in degrees Celsius: "
                                      "K - 273.15)"),
])
def test_a_csv_column_in_another_unit_names_the_conversion(tmp_path, header, needle):
    path = tmp_path / "plant.csv"
    path.write_text(f"{header}\n0.5,10,0.044\n")
    with pytest.raises(InputError) as exc:
        read_measured(str(path))
    assert needle in str(exc.value)


def test_a_request_key_in_another_unit_names_the_conversion():
    with pytest.raises(Invalid) as exc:
        read_calibration({"conveyor": "conveyors/slope-5pct.yaml", "model": "din",
                          "fit": ["f_carry"],
                          "measured": [{"load": 0.5, "temperature_c": 10, "power_MW": 0.044}]})
    assert ("measured.0.power_MW: unknown key 'power_MW'; did you mean 'power_kw'? "
            "(in kW: MW x 1000)") in exc.value.message


@pytest.mark.parametrize("cell,number", [("0,7", "0.7"), ("2,5", "2.5")])
def test_a_load_with_a_decimal_comma_is_named_as_such(tmp_path, cell, number):
    """A load cell '0,7' reads as one fraction per section, [0, 7], and 7 was told 'a fraction,
    not a per cent (7 % of the design load is 0.07)', a tenth of the 0.7 meant. A pair of
    which one is outside 0..1.3 is named as the decimal comma it likely is ('1,0', two
    fractions in range, stays a list)."""
    path = tmp_path / "plant.csv"
    path.write_text(f'load,temperature_c,power_kw\n"{cell}",10,378.8\n0.6,12,419\n')
    from beltstudy.engine.calibration import measurements_from_rows

    with pytest.raises(InputError) as exc:
        measurements_from_rows(read_measured(str(path)))
    assert f"if it is {number} written with a decimal comma, write {number}" in str(exc.value)
    assert exc.value.field == "measured.0.load"
    ok = tmp_path / "ok.csv"
    ok.write_text('load,temperature_c,power_kw\n"1,0",10,378.8\n0.6,12,419\n')
    assert measurements_from_rows(read_measured(str(ok)))[0].load == [1.0, 0.0]


def test_a_temperature_in_kelvin_under_its_celsius_header_is_told_the_celsius(tmp_path,
                                                                            capsys):
    """253.15 under temperature_c named the bound only ('less than or equal to 80 (got
    '253.15')'): a CSV's cells are text, which the unit hint did not read."""
    from beltstudy.service.cli import main
    from tests.conftest import CONVEYORS

    path = tmp_path / "plant.csv"
    path.write_text("load,temperature_c,power_kw\n0.5,253.15,300\n1.0,293.15,600\n")
    assert main(["calibrate", str(CONVEYORS / "slope-5pct.yaml"), "--measured", str(path),
                 "--model", "din", "--fit", "f_carry"]) == 2
    err = capsys.readouterr().err
    assert "(got '253.15'): in degrees Celsius, -20 C if 253.15 is K" in err, err
