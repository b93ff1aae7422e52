"""``beltstudy simulate``'s own check of a run with a concave curve (the CLI over the engine:
kept out of tests/engine, which never imports the service)."""

from __future__ import annotations

from tests.conftest import hand_conveyor_dict


def test_simulate_s_check_gives_the_liftoff_margin_its_error_bar(tmp_path, capsys):
    """``beltstudy simulate`` checks a run by default (engine/accuracy.py): the lift-off
    margin at a concave curve is one of its deciding figures, with its bar in kN, and a
    margin within its bar of 0 kN says ``marginal:`` (PHYSICS 5.2) instead of flipping with
    the mesh. The hand conveyor as 100 m flat then 100 m rising 10 m, a concave curve of R
    80 m (lift-off tension R m'_G g = 15.7 kN), the automatic take-up, a 10 s start on 60
    elements: the drive slips from the start into the stop, the tension at the curve swings
    with the slip, and the margin (-1.3 kN on 70 elements, -2.3 on 48, +0.8 on 150: lifts on
    the finest) gets a bar of about 20 kN, so the run says the verdict is marginal. The
    same conveyor without the curve reports no lift-off figure and no bar."""
    import json

    import yaml

    from beltstudy.service.cli import main

    d = hand_conveyor_dict(profile=[{"length_m": 100, "lift_m": 0, "curve_radius_m": 80},
                                    {"length_m": 100, "lift_m": 10}])
    d["drives"][0].update(rated_power_kw=1000, inertia_kg_m2=200, wrap_deg=240, friction=0.45)
    path = tmp_path / "valley.yaml"

    def simulate(data) -> dict:
        path.write_text(yaml.safe_dump(data))
        assert main(["simulate", str(path), "--start-time-s", "10", "--run-s", "3",
                     "--elements", "60", "--no-remedy", "--json"]) in (0, 1)
        return json.loads(capsys.readouterr().out)

    s = simulate(d)
    over, err = s["liftoff_max_kn_over"], s["liftoff_max_kn_over_err"]
    assert over is not None and err is not None and err > 0.0, s["accuracy_methods"]
    assert "liftoff_max_kn_over" in s["accuracy_methods"]
    assert "liftoff_max_kn_over_converged" in s
    marginal = (f"marginal: liftoff_max_kn_over {over:.4g} against limit 0 +- {err:.3g} kN "
                "(the verdict may flip with the mesh; ")
    assert (marginal in s["message"]) is (abs(over) <= err)
    assert abs(over) <= err and s["status"] == "warning"  # this margin is within its bar
    d["profile"] = [{"length_m": 200, "lift_m": 10}]
    s = simulate(d)
    assert "accuracy_elements" in s and s["liftoff_max_kn_over"] is None
    assert s.get("liftoff_max_kn_over_err") is None
    assert "marginal: liftoff" not in s["message"]
