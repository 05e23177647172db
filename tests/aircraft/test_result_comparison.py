"""Comparing two results folders within a tolerance (``aircraft.result_comparison``).

Every difference below is made by hand in the candidate folder, so the oracle is
independent of the code under test: we know which file, column, row and values
moved, and by how much.
"""
import math

import pytest

from aircraft.result_comparison import Tolerance, compare_folders

TABLE = ("case,x,y,label,wall_s\n"
         "A,1.0,0.5,alpha,3.2\n"
         "B,2.0,,beta,4.1\n"
         "C,3.0,-0.25,gamma,5.0\n")


def _folders(tmp_path, candidate_table=TABLE, extra=None):
    ref, new = tmp_path / "ref", tmp_path / "new"
    for folder, table in ((ref, TABLE), (new, candidate_table)):
        folder.mkdir()
        (folder / "table.csv").write_text(table)
        (folder / "notes.txt").write_text("converged\n")
        (folder / "figure.png").write_bytes(bytes([folder == ref]))   # figures differ in bytes
    for name, text in (extra or {}).items():
        (new / name).write_text(text)
    return ref, new


def _row(result, file, column):
    table = result.to_pandas()
    match = table[(table.file == file) & (table.column == column)]
    assert len(match) == 1, table
    return match.iloc[0]


def test_identical_folders_pass(tmp_path):
    result = compare_folders(*_folders(tmp_path))
    assert result.passes and result.moved().empty
    table = result.to_pandas()
    assert set(table[table.kind.isin(["numeric", "text"])].verdict) == {"same"}
    assert _row(result, "figure.png", "").verdict == "not compared"
    assert _row(result, "notes.txt", "").verdict == "same"
    assert "0 moved" in result.report() and "reproduced within tolerance" in result.report()


def test_round_off_passes_and_a_real_change_is_located(tmp_path):
    small = TABLE.replace("A,1.0,", "A,1.000000000001,")        # 1e-12: round-off
    result = compare_folders(*_folders(tmp_path, small))
    assert result.passes
    row = _row(result, "table.csv", "x")
    assert row.verdict == "within tolerance" and row.max_abs == pytest.approx(1e-12, rel=1e-3)

    moved = TABLE.replace("C,3.0,", "C,3.003,")                 # 1e-3 relative, row 2
    (tmp_path / "b").mkdir()
    result = compare_folders(*_folders(tmp_path / "b", moved))
    assert not result.passes
    bad = result.moved()
    assert bad[["file", "column", "row"]].values.tolist() == [["table.csv", "x", 2]]
    assert bad.reference[0] == 3.0 and bad.candidate[0] == 3.003
    assert bad.max_abs[0] == pytest.approx(0.003) and bad.max_rel[0] == pytest.approx(1e-3)
    assert _row(result, "table.csv", "y").verdict == "same"
    text = result.report()
    assert "1 moved" in text and "table.csv, column 'x'" in text and "at row 2: 3.0 -> 3.003" in text


def test_nan_equals_nan_but_not_a_number(tmp_path):
    # the reference's y at row 1 is NaN (an empty entry); "nan" written out is the same
    same = TABLE.replace("B,2.0,,", "B,2.0,nan,")
    assert compare_folders(*_folders(tmp_path, same)).passes
    (tmp_path / "b").mkdir()
    filled = TABLE.replace("B,2.0,,", "B,2.0,0.5,")
    result = compare_folders(*_folders(tmp_path / "b", filled))
    bad = result.moved()
    assert bad[["column", "row"]].values.tolist() == [["y", 1]]
    assert math.isnan(bad.reference[0]) and bad.candidate[0] == 0.5


def test_infinity_equals_only_the_same_infinity(tmp_path):
    ref = tmp_path / "ref"
    ref.mkdir()
    (ref / "t.csv").write_text("v\ninf\n-inf\n")
    for k, (text, passes) in enumerate((("v\ninf\n-inf\n", True), ("v\ninf\ninf\n", False),
                                        ("v\ninf\n1e308\n", False))):
        new = tmp_path / f"new{k}"
        new.mkdir()
        (new / "t.csv").write_text(text)
        assert compare_folders(ref, new).passes is passes, text


def test_a_text_change_is_exact(tmp_path):
    result = compare_folders(*_folders(tmp_path, TABLE.replace("beta", "Beta")))
    bad = result.moved()
    assert bad[["column", "kind", "row", "reference", "candidate"]].values.tolist() == [
        ["label", "text", 1, "beta", "Beta"]]


def test_a_changed_text_file_is_reported(tmp_path):
    ref, new = _folders(tmp_path)
    (new / "notes.txt").write_text("not converged\n")
    bad = compare_folders(ref, new).moved()
    assert bad[["file", "row", "reference", "candidate"]].values.tolist() == [
        ["notes.txt", 0, "converged", "not converged"]]


def test_a_missing_file_an_extra_column_and_a_length_change_are_differences(tmp_path):
    with_z = ("case,x,y,label,wall_s,z\n"
              "A,1.0,0.5,alpha,3.2,9\n"
              "B,2.0,,beta,4.1,9\n"
              "C,3.0,-0.25,gamma,5.0,9\n")
    ref, new = _folders(tmp_path, with_z)
    (ref / "gone.csv").write_text("a\n1\n")
    result = compare_folders(ref, new)
    bad = result.moved()
    assert sorted(map(tuple, bad[["file", "column", "verdict", "detail"]].values.tolist())) == [
        ("gone.csv", "", "missing", "only in the reference"),
        ("table.csv", "z", "missing", "only in the candidate")]
    assert not result.passes and "2 missing" in result.report()
    (tmp_path / "b").mkdir()
    longer = compare_folders(*_folders(tmp_path / "b", TABLE + "D,4.0,1.0,delta,6.0\n"))
    assert longer.moved().detail.tolist() == ["3 rows in the reference, 4 in the candidate"]


def test_timing_columns_are_not_compared(tmp_path):
    ref, new = tmp_path / "ref", tmp_path / "new"
    for folder, times in ((ref, "1.0,2.0,3.0,4.0,True"), (new, "9.0,8.0,7.0,6.0,False")):
        folder.mkdir()
        (folder / "t.csv").write_text("wall_s,wall_time_s,search_wall_s,wall_time,wake_cache,x\n" + times + ",1\n")
    result = compare_folders(ref, new)
    assert result.passes
    table = result.to_pandas().set_index("column")
    assert (table.loc[["wall_s", "wall_time_s", "search_wall_s", "wall_time", "wake_cache"], "kind"] == "timing").all()
    assert table.loc["x", "verdict"] == "same"


def test_a_file_qualified_tolerance_beats_the_generic_pattern(tmp_path):
    moved = TABLE.replace("C,3.0,", "C,3.003,")                  # x moves by 1e-3 relative
    ref, new = _folders(tmp_path, moved)
    (ref / "other.csv").write_text(TABLE)
    (new / "other.csv").write_text(moved)
    tolerances = {"x": Tolerance(rtol=1e-2), "table.csv:[xy]": (1e-4, 0.0)}
    result = compare_folders(ref, new, tolerances=tolerances)
    # table.csv's x is held to the file-qualified 1e-4 (moved); other.csv's x to the generic 1e-2
    assert result.moved()[["file", "column"]].values.tolist() == [["table.csv", "x"]]
    assert _row(result, "table.csv", "x").rtol == 1e-4
    assert _row(result, "other.csv", "x").verdict == "within tolerance"
    assert _row(result, "other.csv", "y").rtol == 1e-6                  # no pattern: the default


def test_complex_columns_compare_on_the_modulus(tmp_path):
    ref, new = tmp_path / "ref", tmp_path / "new"
    for folder, pole in ((ref, "(-0.5+2j)"), (new, "(-0.5000000000001+2j)")):
        folder.mkdir()
        (folder / "t.csv").write_text(f"pole\n{pole}\n0j\n")
    row = _row(compare_folders(ref, new), "t.csv", "pole")
    assert row.kind == "complex" and row.verdict == "within tolerance"


@pytest.mark.parametrize("kwargs, name", [({"rtol": -1e-6}, "rtol"), ({"atol": math.nan}, "atol"),
                                          ({"rtol": math.inf}, "rtol"), ({"atol": "1e-9"}, "atol")])
def test_an_invalid_tolerance_is_refused(kwargs, name):
    with pytest.raises(ValueError, match=f"Tolerance {name} must be a finite number >= 0"):
        Tolerance(**kwargs)


def test_an_invalid_pattern_tolerance_and_a_missing_folder_are_refused(tmp_path):
    ref, new = _folders(tmp_path)
    with pytest.raises(ValueError, match="tolerance 'x' must be a Tolerance"):
        compare_folders(ref, new, tolerances={"x": 1e-3})
    with pytest.raises(FileNotFoundError, match="does not exist"):
        compare_folders(ref, tmp_path / "nowhere")
