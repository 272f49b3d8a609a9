#!/usr/bin/env python3
"""Writes the sensitivity band's runs from the as-built cases: runs/<name>.toml from
cases/lever_chain_manipulator_as_built, runs_four_bar/<name>.toml from
cases/lever_manipulator_as_built.

Each run is the case file with the changes of one band point: one unknown at a time, then the
combined extremes (README.md). The vibration and fatigue
stages are off (the band is over the peak von Mises and the deformation). Run it again after
editing the case:

    python3 cases/sensitivity/as_built_band/generate.py
"""
import pathlib
import re

HERE = pathlib.Path(__file__).resolve().parent
BASE = HERE.parent.parent / "lever_chain_manipulator_as_built" / "case.toml"
CASE_PARTS = "../../../lever_chain_manipulator_as_built/parts/"   # from runs/
BASE_FOUR_BAR = HERE.parent.parent / "lever_manipulator_as_built" / "case.toml"
CASE_PARTS_FOUR_BAR = "../../../lever_manipulator_as_built/parts/"
BAND_PARTS = "../parts/"

# Each change: (a regular expression that must match exactly once, or `count` times, its replacement).
def pin_a(d):
    return [(r'(joint = "A"\ndiameter_mm = )30\.0', rf'\g<1>{d:.1f}')]

def pin_a0(d):
    return [(r'(joint = "A0"\ndiameter_mm = )40\.0', rf'\g<1>{d:.1f}')]

def lever_file(variant):
    return [(r'file = "[^"]*lever\.step"', f'file = "{BAND_PARTS}{variant}_lever.step"')]

def arm_plane(dz):
    # The arm and the gripper move out along the pins by dz; the chain's anchor stud grows with
    # them (a frame variant), so the chain stays in the roller's plane.
    return [(r'offset_mm = \[0\.0, 0\.0, 245\.0\]', f'offset_mm = [0.0, 0.0, {245 + dz:.1f}]', 2),
            (r'file = "[^"]*frame\.step"', f'file = "{BAND_PARTS}chain{211 + dz}_frame.step"'),
            (r'box_mm = \[49\.5, 62\.735, 210\.5, 100\.5, 113\.735, 211\.5\]',
             f'box_mm = [49.5, 62.735, {210.5 + dz}, 100.5, 113.735, {211.5 + dz}]')]

def casting(m):
    return [(r'(name = "casting"\nmass_kg = )5\.0', rf'\g<1>{m:.1f}')]

def column_modulus(e_mpa):
    # The frame's stiffness: the column's modulus (its bending stiffness E I scales with it; the
    # mass does not change).
    return [(r'(name = "column"\ninside_mm = \[76\.0, 0\.0, 0\.0\][^\n]*\n)',
             rf'\g<1>youngs_modulus_mpa = {e_mpa:.1f}\npoisson_ratio = 0.3\ndensity_kg_m3 = 7850.0\n')]

def chain_ea(ea):
    return [(r'ea_per_strand_n = 5\.0e6', f'ea_per_strand_n = {ea:.3g}')]

def pins_in_contact(clearance, revolute_joints):
    # Every revolute pin in frictionless contact with its bores (docs/contact.md): line-to-line
    # (0), an ISO 286 fit, or a radial clearance in mm.
    key = f'fit = "{clearance}"' if isinstance(clearance, str) else f'clearance_mm = {clearance}'
    return [(r'(type = "revolute"\n)', rf'\g<1>load = "contact"\n{key}\n', revolute_joints)]

CONTACT = {"pins_contact_line": 0.0, "pins_contact_H7g6": "H7/g6", "pins_contact_50um": 0.05}

ONE_AT_A_TIME = {
    "pin_A_20": pin_a(20.0),
    "pin_A_25": pin_a(25.0),
    "pin_A0_30": pin_a0(30.0),
    "lug_A_20": lever_file("lug20"),
    "lug_A_30": lever_file("lug30"),
    "lever_plate_12": lever_file("plate12"),
    "lever_plate_25": lever_file("plate25"),
    "arm_plane_plus20": arm_plane(20),
    "arm_plane_plus40": arm_plane(40),
    "casting_2kg": casting(2.0),
    "casting_15kg": casting(15.0),
    "column_E_x0.5": column_modulus(105000.0),
    "column_E_x2": column_modulus(420000.0),
    "chain_EA_x0.25": chain_ea(1.25e6),
    "chain_EA_x4": chain_ea(2.0e7),
    **{name: pins_in_contact(c, 2) for name, c in CONTACT.items()},
}
# The four-bar: the unknowns it shares with the lever-chain (no chain; the plane offsets would
# need frame variants and are not run).
def pin(joint, d_case, d):
    return [(rf'(joint = "{joint}"\ndiameter_mm = ){d_case:.1f}', rf'\g<1>{d:.1f}')]

def part_file(part, variant):
    return [(rf'file = "[^"]*/{part}\.step"', f'file = "{BAND_PARTS}{variant}_{part}.step"')]

FOUR_BAR = {
    "pin_A_20": pin("A", 30.0, 20.0),
    "pin_B_B0_20": pin("B", 25.0, 20.0) + pin("B0", 25.0, 20.0),
    "pin_A0_30": pin("A0", 40.0, 30.0),
    "lever_plate_12": part_file("lever", "fourbar_plate12"),
    "lever_plate_25": part_file("lever", "fourbar_plate25"),
    "rocker_plate_8": part_file("rocker", "fourbar_rocker8"),
    "rocker_plate_20": part_file("rocker", "fourbar_rocker20"),
    "casting_2kg": casting(2.0),
    "casting_15kg": casting(15.0),
    "column_E_x0.5": column_modulus(105000.0),
    "column_E_x2": column_modulus(420000.0),
    **{name: pins_in_contact(c, 4) for name, c in CONTACT.items()},
    "all_soft": pin("A", 30.0, 20.0) + pin("B", 25.0, 20.0) + pin("B0", 25.0, 20.0) + pin("A0", 40.0, 30.0)
                + part_file("lever", "fourbar_plate12") + part_file("rocker", "fourbar_rocker8") + casting(15.0)
                + column_modulus(105000.0),
    "all_stiff": part_file("lever", "fourbar_plate25") + part_file("rocker", "fourbar_rocker20") + casting(2.0)
                 + column_modulus(420000.0),
}

# The combined extremes: every unknown at its soft/weak end, and at its stiff/strong end. Two
# unknowns act on one file (the lever's plate and its lug): the soft end takes the thinner lug
# (the lug is the detail at the pin), the stiff end the thicker plate.
COMBINED = {
    "all_soft": pin_a(20.0) + pin_a0(30.0) + lever_file("lug20") + arm_plane(40) + casting(15.0)
                + column_modulus(105000.0) + chain_ea(1.25e6),
    "all_stiff": lever_file("plate25") + casting(2.0) + column_modulus(420000.0) + chain_ea(2.0e7),
}


def stages_off(text):
    for table in ("vibration", "fatigue"):
        text, n = re.subn(rf'(\[{table}\][^\n]*\nenabled = )true', r'\g<1>false', text)
        assert n == 1, table
    return text


def write(name, changes, base, folder="runs", case="lever_chain_manipulator_as_built", parts=CASE_PARTS):
    text = base.replace('file = "parts/', f'file = "{parts}')
    text, n = re.subn(rf'name = "{case}"', f'name = "band_{name}"', text, count=1)
    assert n == 1, name
    for change in changes:
        pattern, replacement = change[0], change[1]
        count = change[2] if len(change) > 2 else 1
        text, n = re.subn(pattern, replacement, text)
        assert n == count, (name, pattern, n)
    text = stages_off(text)
    header = (f"# Generated by cases/sensitivity/as_built_band/generate.py from "
              f"cases/{case}/case.toml: band point '{name}'. Do not edit.\n")
    (HERE / folder / f"{name}.toml").write_text(header + text)


def main():
    for folder in ("runs", "runs_four_bar"):
        (HERE / folder).mkdir(exist_ok=True)
        for old in (HERE / folder).glob("*.toml"):
            old.unlink()
    base = BASE.read_text()
    write("reference", [], base)
    for name, changes in {**ONE_AT_A_TIME, **COMBINED}.items():
        write(name, changes, base)
    four_bar = dict(folder="runs_four_bar", case="lever_manipulator_as_built", parts=CASE_PARTS_FOUR_BAR)
    base = BASE_FOUR_BAR.read_text()
    write("four_bar_reference", [], base, **four_bar)
    for name, changes in FOUR_BAR.items():
        write("four_bar_" + name, changes, base, **four_bar)


if __name__ == "__main__":
    main()
