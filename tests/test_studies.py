from studies.identification_demo import run_demo


def test_identification_demo_writes_tables_and_figures(tmp_path):
    cost = run_demo(seed=3, out_dir=tmp_path, verbose=False)
    assert len(cost) == 12 and cost.J.mean() < 10
    for name in ("cost_table.csv", "parameters.csv", "verification.csv", "reduction_log.csv",
                 "bode_fit.png", "verification.png"):
        assert (tmp_path / name).stat().st_size > 0


# The wake identification chain is tested on the library pipeline
# (tests/test_identification_pipeline.py: aircraft.identify_inflow on a tiny wake).
