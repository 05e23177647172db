"""Write spec_table.csv (controllers.hq.spec_table) and its manifest; run once after a library change.

    python results/hq_spec_library/make_table.py

tests/test_hq_specs.py checks that the committed CSV equals spec_table().
"""
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))

from aircraft.provenance import write_manifest   # noqa: E402
from controllers.hq import spec_table            # noqa: E402

if __name__ == "__main__":
    t0 = time.perf_counter()
    (HERE / "spec_table.csv").write_text(spec_table().to_csv(index=False, lineterminator="\n"))
    write_manifest(HERE, command="python results/hq_spec_library/make_table.py", settings={"options": []},
                   wall_time_s=time.perf_counter() - t0)
