from studies.identification_demo import run_demo


def test_identification_demo_writes_tables_and_figures(tmp_path):
    cost = run_demo(seed=3, out_dir=tmp_path, verbose=False)
    assert len(cost) == 12 and cost.J.mean() < 10
    for name in ("cost_table.csv", "parameters.csv", "verification.csv", "reduction_log.csv",
                 "bode_fit.png", "verification.png"):
        assert (tmp_path / name).stat().st_size > 0


def test_wake_identification_pipeline_on_a_coarse_wake(tmp_path):
    # Mission steps 1-2 on our own wake at a coarse resolution (15 deg steps, 1.5
    # revs of wake, 5 elements, 36 s sweeps): the pipeline must run end to end and
    # identify Pitt-Peters-signed coefficients; the quasi-steady gain 1/Lbar11 must
    # be within 30 % of momentum 1/(4 lambda_h) (the issue-3 requirement; the
    # dissertation's MFW gave 14 %).
    import math
    from aircraft.wake import WakeSettings
    from studies.wake_identification import run_study
    settings = WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=1.5, n_elements=5)
    table, result = run_study(settings, sweep_s=36.0, out_dir=tmp_path, n_jobs=1,
                              cache_dir=None, progress=False, verbose=False)
    coef = table.set_index("coefficient")["identified from our wake"]
    assert coef["M11/Omega [s]"] > 0 and coef["M22/Omega [s]"] < 0
    assert coef["Lbar11"] > 0 and coef["Lbar22"] < 0
    lam_h = math.sqrt(0.0061 / 2)
    assert abs(1.0 / coef["Lbar11"] / (1.0 / (4 * lam_h)) - 1) < 0.30
    assert result.J_ave < 100
    for name in ("coefficients.csv", "cost_table.csv", "verification.csv", "bode_fit.png"):
        assert (tmp_path / name).stat().st_size > 0
