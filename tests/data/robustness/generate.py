# Generates the bad-input catalogue tests/data/robustness/<nn>_<what>/ (case files, hand-written .msh files, expected.txt). Run from anywhere: python3 generate.py
import os, itertools
ROOT = os.path.dirname(os.path.abspath(__file__))

FE = """[case]
name = "r"
type = "fe_static"

[geometry]
kind = "lever"
length_mm = 500.0
width_mm = 80.0
thickness_mm = 25.0
bore_diameter_mm = 40.0
boss_diameter_mm = 90.0
boss_length_mm = 50.0

[mesh]
element_size_mm = 20.0
order = 1

[material]
youngs_modulus_mpa = 210000.0
poisson_ratio = 0.3
density_kg_m3 = 7850.0

[[support]]
set = "bore_A0"
fixed = ["x", "y", "z"]

[[force]]
set = "bore_A"
total_n = [-2000.0, 0.0, 0.0]
"""

MAN = """[case]
name = "r"
type = "manipulator"

[mechanism]
type = "lever_chain"
a_mm = 500.0
c_mm = 350.0
h_mm = 100.0
r_mm = 75.0
gravity_m_s2 = [0.0, -9.80665, 0.0]

[payload]
gripper_mass_kg = 20.0
casting_mass_kg = 15.0

[motion]
law = "polynomial345"
stroke_deg = 80.0
duration_s = 2.0
output_times = 11

[mesh]
element_size_mm = 20.0
order = 1

[static_study]
enabled = false
"""

# Cube 0.1 m, 6 Kuhn tets; nodes tag = 1 + (x + 2y + 4z).
def cube_msh(inverted=False, groups=True, bad_node_ref=False, nan_coord=False, volume=True,
             truncate=None, dup_names=False):
    P = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    P = [(0.1 * x, 0.1 * y, 0.1 * z) for (x, y, z) in P]
    tets = [(0, 1, 3, 7), (0, 1, 5, 7), (0, 2, 3, 7), (0, 2, 6, 7), (0, 4, 5, 7), (0, 4, 6, 7)]
    def vol(t):
        a, b, c, d = [P[i] for i in t]
        u = [b[k] - a[k] for k in range(3)]; v = [c[k] - a[k] for k in range(3)]; w = [d[k] - a[k] for k in range(3)]
        return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]))
    tets = [t if vol(t) > 0 else (t[1], t[0], t[2], t[3]) for t in tets]
    if inverted:
        t = tets[2]; tets[2] = (t[1], t[0], t[2], t[3])
    bottom = [(0, 3, 1), (0, 2, 3)]
    top = [(4, 5, 7), (4, 7, 6)]
    L = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat"]
    if groups:
        n2 = '"fixed"' if not dup_names else '"loaded"'
        L += ["$PhysicalNames", "3", f"2 1 {n2}", '2 2 "loaded"', '3 3 "body"', "$EndPhysicalNames"]
    pt = lambda tag: f"1 {tag}" if groups else "0"
    L += ["$Entities", "0 0 2 1",
          f"1 0 0 0 0.1 0.1 0 {pt(1)} 0",
          f"2 0 0 0.1 0.1 0.1 0.1 {pt(2)} 0",
          f"1 0 0 0 0.1 0.1 0.1 {pt(3)} 2 1 2",
          "$EndEntities"]
    L += ["$Nodes", "2 8 1 8", "2 1 0 4"] + [str(i + 1) for i in range(4)]
    for i in range(4):
        x, y, z = P[i]
        L.append(f"{x:g} {y:g} {z:g}" if not (nan_coord and i == 1) else f"nan {y:g} {z:g}")
    L += ["2 2 0 4"] + [str(i + 1) for i in range(4, 8)]
    L += [" ".join(f"{c:g}" for c in P[i]) for i in range(4, 8)]
    L += ["$EndNodes"]
    nblocks = 3 if volume else 2
    nel = 4 + (6 if volume else 0)
    L += ["$Elements", f"{nblocks} {nel} 1 {nel}", "2 1 2 2"]
    L += [f"{k + 1} " + " ".join(str(i + 1) for i in f) for k, f in enumerate(bottom)]
    L += ["2 2 2 2"] + [f"{k + 3} " + " ".join(str(i + 1) for i in f) for k, f in enumerate(top)]
    if volume:
        L += ["3 1 4 6"]
        for k, t in enumerate(tets):
            nodes = [i + 1 for i in t]
            if bad_node_ref and k == 3: nodes[3] = 99
            L.append(f"{k + 5} " + " ".join(map(str, nodes)))
    L += ["$EndElements"]
    text = "\n".join(L) + "\n"
    if truncate: text = text[: text.index(truncate)]
    return text

CUBE = """[case]
name = "r"
type = "fe_static"

[geometry]
kind = "file"
file = "cube.msh"

[mesh]
order = 1

[material]
youngs_modulus_mpa = 210000.0
poisson_ratio = 0.3

[[support]]
set = "fixed"
fixed = ["x", "y", "z"]

[[force]]
set = "loaded"
total_n = [0.0, 0.0, 1000.0]
"""

def sub(base, old, new):
    assert old in base, old
    return base.replace(old, new, 1)

E = {'malformed_toml_unclosed_table': "case.toml:18:10: TOML syntax error: Error while parsing table header: expected ']'", 'malformed_toml_duplicate_key': "case.toml:21:17: TOML syntax error: Error while parsing key-value pair: cannot redefine existing floating-point 'poisson_ratio'", 'malformed_toml_unterminated_string': 'case.toml:28:14: TOML syntax error: Error while parsing string', 'malformed_toml_binary_garbage': 'case.toml:3:1: TOML syntax error: Error while parsing root table', 'empty_case_file': "case.toml: required key 'case.type' is missing", 'unknown_key_typo': 'case.toml:15: unknown key \'mesh.element_sise_mm\' (allowed here: "element_size_mm"', 'unknown_table': "case.toml:18: unknown key 'materials' (allowed here:", 'missing_case_type': "case.toml: required key 'case.type' is missing", 'unknown_case_type': 'case.toml: case.type = "fe_statik" is not a known case type', 'missing_force_total': "case.toml: key 'force[0].total_n' is required", 'missing_mechanism_type': "case.toml: required key 'mechanism.type' is missing", 'mistyped_string_for_number': "case.toml:15: key 'mesh.element_size_mm' must be a number (in mm)", 'mistyped_float_for_integer': "case.toml:16: key 'mesh.order' must be an integer", 'mistyped_table_for_array_of_tables': "case.toml:23: key 'support' must be an array of tables ([[support]])", 'mistyped_vector_two_components': "case.toml:29: key 'force[].total_n' must be an array of 3 numbers", 'mistyped_axis_name': 'case.toml:25: key \'support[].fixed\' holds "w": use only "x", "y", "z"', 'geometry_file_key_missing': 'case.toml: key \'geometry.file\' is required when geometry.kind = "file"', 'zero_length': "case.toml:7: key 'geometry.length_mm' = 0 mm is out of range: must be >0", 'negative_thickness': "case.toml:9: key 'geometry.thickness_mm' = -25 mm is out of range: must be >0", 'negative_density': "case.toml:21: key 'material.density_kg_m3' = -7850 kg/m^3 is out of range: must be 0, or >=1 and <=100000 kg/m^3 (0 for a massless part, else plausible for a solid: osmium is 22 590 kg/m^3)", 'zero_youngs_modulus': "case.toml:19: key 'material.youngs_modulus_mpa' = 0 MPa is out of range: must be >=0.001 and <=1e+07 MPa (plausible for a solid: from a soft gel to above diamond)", 'poisson_ratio_half': "case.toml:20: key 'material.poisson_ratio' = 0.5 is out of range: must be >-1 and <=0.4999", 'poisson_ratio_above_half': "case.toml:20: key 'material.poisson_ratio' = 0.7 is out of range: must be >-1 and <=0.4999", 'negative_element_size': "case.toml:15: key 'mesh.element_size_mm' = -20 mm is out of range: must be >0", 'bore_larger_than_boss': 'case.toml: [geometry]: lever bore_diameter_m = 0.095 must be smaller than width_m = 0.08', 'negative_payload_mass': "case.toml:15: key 'payload.casting_mass_kg' = -15 kg is out of range: must be >=0 and <=1e+06 kg (a plausible mass: up to 1000 t)", 'zero_lever_length_manipulator': "case.toml:7: key 'mechanism.a_mm' = 0 mm is out of range: must be >0 and <=1e+06 mm (a plausible length: up to 1 km)", 'zero_duration': "case.toml:20: key 'motion.duration_s' = 0 s is out of range: must be >0 and <=1e+07 s (a plausible time: up to about 4 months)", 'one_output_time': "case.toml:21: key 'motion.output_times' = 1 is out of range: must be >=2 and <=100000", 'trapezoid_fractions_over_one': 'case.toml:18: key \'motion.law\': motion law "trapezoidal": accel_fraction 0.7 and decel_fraction 0.6 must be positive with a sum of at most 1', 'gravity_out_of_plane': "case.toml:11: key 'mechanism.gravity_m_s2' = [0, -9.80665, 1]: the z component (along the pins) must be 0", 'nan_youngs_modulus': "case.toml:19: key 'material.youngs_modulus_mpa' = nan is not a finite number", 'inf_force': "case.toml:29: key 'force[].total_n' = inf is not a finite number", 'negative_inf_gravity_manipulator': "case.toml:11: key 'mechanism.gravity_m_s2' = -inf is not a finite number", 'nan_stroke': "case.toml:19: key 'motion.stroke_deg' = nan is not a finite number", 'lever_stroke_past_assembly_limit': "case.toml: the motion cannot be run: mechanism 'lever manipulator': singular position at t = 1.52", 'lever_dead_centre_in_motion': "case.toml: the motion cannot be run: mechanism 'lever manipulator': singular position at t = 1.958", 'lever_dead_centre_kinetostatic': "case.toml: the motion cannot be run: mechanism 'lever manipulator': singular position at t = 1.958", 'lever_chain_slack_gravity_reversed': "case.toml: the motion cannot be run: mechanism 'lever-chain manipulator': chain 'chain' goes slack at t = 0 s", 'lever_chain_inconsistent_dimensions': "case.toml: [links]: part 'arm' (link 2 with roller): arm length_m = 0.05 must exceed", 'rigid_body_modes_left': 'no support fixes displacements along y, z', 'no_supports': 'case.toml: no [[support]]: a static model needs supports', 'support_set_not_in_mesh': 'case.toml:24: key \'support[0].set\' = "bore_B": the mesh has no node set of that name (present: bore_A, bore_A0', 'factor_exceeds_memory_limit': 'more than the 0.001 GB allowed', 'msh_missing': 'cube.msh: no such mesh file', 'msh_empty': 'cube.msh: the mesh file is empty', 'msh_not_a_mesh': 'cube.msh: not a Gmsh .msh file (it does not start with $MeshFormat)', 'msh_truncated': 'cube.msh: the mesh file is truncated', 'msh_corrupt_node_line': "cube.msh: $Entities: an entity's coordinates: 'zz' is not a number", 'msh_inverted_tet': 'cube.msh: element 2 (TET4) is inverted or degenerate', 'msh_without_physical_groups': 'case.toml:17: key \'support[0].set\' = "fixed": the mesh has no node set of that name (present: none)', 'msh_element_refers_to_missing_node': 'cube.msh: $Elements: element 8 refers to node 99, which the file does not hold', 'msh_nan_coordinate': 'cube.msh: mesh node 1 has a non-finite coordinate', 'msh_surface_only': 'cube.msh: the mesh has no volume elements', 'msh_duplicate_group_name': "cube.msh: physical group name 'loaded' is used twice", 'case_file_missing': 'nothere.toml: case file does not exist', 'case_path_is_directory': 'sub: is a directory, expected a case file', 'output_dir_under_regular_file': '@FILE@/out: cannot create the output directory: Not a directory', 'output_dir_in_proc': '/proc/kinetofem-out: cannot create the output directory', 'disk_full_fe_static': "@OUT@/r.h5': file write failed: File too large", 'disk_full_manipulator': "@OUT@/r.h5': file write failed: File too large"}
cases = []  # (dir, files{name: text}, expected, extra{args, limits})
def add(name, files, expected="?", **extra):
    cases.append((name, files, E[name], extra))

# --- TOML syntax
add("malformed_toml_unclosed_table", {"case.toml": sub(FE, "[material]", "[material")})
add("malformed_toml_duplicate_key", {"case.toml": sub(FE, "poisson_ratio = 0.3", "poisson_ratio = 0.3\npoisson_ratio = 0.25")})
add("malformed_toml_unterminated_string", {"case.toml": sub(FE, 'set = "bore_A"', 'set = "bore_A')})
add("malformed_toml_binary_garbage", {"case.toml": "[case]\ntype = \"fe_static\"\n\x01\x02\xff\xfe = 3\n"})
add("empty_case_file", {"case.toml": ""})
# --- keys
add("unknown_key_typo", {"case.toml": sub(FE, "element_size_mm = 20.0", "element_sise_mm = 20.0")})
add("unknown_table", {"case.toml": sub(FE, "[material]", "[materials]")})
add("missing_case_type", {"case.toml": sub(FE, 'type = "fe_static"\n', "")})
add("unknown_case_type", {"case.toml": sub(FE, 'type = "fe_static"', 'type = "fe_statik"')})
add("missing_force_total", {"case.toml": sub(FE, "total_n = [-2000.0, 0.0, 0.0]\n", "")})
add("missing_mechanism_type", {"case.toml": sub(MAN, 'type = "lever_chain"\n', "")})
add("mistyped_string_for_number", {"case.toml": sub(FE, "element_size_mm = 20.0", 'element_size_mm = "20"')})
add("mistyped_float_for_integer", {"case.toml": sub(FE, "order = 1", "order = 1.5")})
add("mistyped_table_for_array_of_tables", {"case.toml": sub(FE, "[[support]]", "[support]")})
add("mistyped_vector_two_components", {"case.toml": sub(FE, "total_n = [-2000.0, 0.0, 0.0]", "total_n = [-2000.0, 0.0]")})
add("mistyped_axis_name", {"case.toml": sub(FE, 'fixed = ["x", "y", "z"]', 'fixed = ["x", "y", "w"]')})
add("geometry_file_key_missing", {"case.toml": sub(FE, 'kind = "lever"', 'kind = "file"')})
# --- values
add("zero_length", {"case.toml": sub(FE, "length_mm = 500.0", "length_mm = 0.0")})
add("negative_thickness", {"case.toml": sub(FE, "thickness_mm = 25.0", "thickness_mm = -25.0")})
add("negative_density", {"case.toml": sub(FE, "density_kg_m3 = 7850.0", "density_kg_m3 = -7850.0")})
add("zero_youngs_modulus", {"case.toml": sub(FE, "youngs_modulus_mpa = 210000.0", "youngs_modulus_mpa = 0.0")})
add("poisson_ratio_half", {"case.toml": sub(FE, "poisson_ratio = 0.3", "poisson_ratio = 0.5")})
add("poisson_ratio_above_half", {"case.toml": sub(FE, "poisson_ratio = 0.3", "poisson_ratio = 0.7")})
add("negative_element_size", {"case.toml": sub(FE, "element_size_mm = 20.0", "element_size_mm = -20.0")})
add("bore_larger_than_boss", {"case.toml": sub(FE, "bore_diameter_mm = 40.0", "bore_diameter_mm = 95.0")})
add("negative_payload_mass", {"case.toml": sub(MAN, "casting_mass_kg = 15.0", "casting_mass_kg = -15.0")})
add("zero_lever_length_manipulator", {"case.toml": sub(MAN, "a_mm = 500.0", "a_mm = 0.0")})
add("zero_duration", {"case.toml": sub(MAN, "duration_s = 2.0", "duration_s = 0.0")})
add("one_output_time", {"case.toml": sub(MAN, "output_times = 11", "output_times = 1")})
add("trapezoid_fractions_over_one", {"case.toml": sub(MAN, 'law = "polynomial345"', 'law = "trapezoidal"\naccel_fraction = 0.7\ndecel_fraction = 0.6')})
add("gravity_out_of_plane", {"case.toml": sub(MAN, "gravity_m_s2 = [0.0, -9.80665, 0.0]", "gravity_m_s2 = [0.0, -9.80665, 1.0]")})
# --- NaN / Inf
add("nan_youngs_modulus", {"case.toml": sub(FE, "youngs_modulus_mpa = 210000.0", "youngs_modulus_mpa = nan")})
add("inf_force", {"case.toml": sub(FE, "total_n = [-2000.0, 0.0, 0.0]", "total_n = [inf, 0.0, 0.0]")})
add("negative_inf_gravity_manipulator", {"case.toml": sub(MAN, "gravity_m_s2 = [0.0, -9.80665, 0.0]", "gravity_m_s2 = [0.0, -inf, 0.0]")})
add("nan_stroke", {"case.toml": sub(MAN, "stroke_deg = 80.0", "stroke_deg = nan")})
# --- mechanisms
add("lever_stroke_past_assembly_limit", {"case.toml": sub(sub(MAN, 'type = "lever_chain"', 'type = "lever"'), "stroke_deg = 80.0", "stroke_deg = 40.0")})
add("lever_dead_centre_in_motion", {"case.toml": sub(sub(sub(MAN, 'type = "lever_chain"', 'type = "lever"'), "stroke_deg = 80.0", "stroke_deg = 36.425"), "output_times = 11", "output_times = 101")})
add("lever_dead_centre_kinetostatic", {"case.toml": sub(sub(sub(MAN, 'type = "lever_chain"', 'type = "lever"'), "stroke_deg = 80.0", "stroke_deg = 36.425"), "output_times = 11", "output_times = 101\n\n[dynamics]\nmethod = \"kinetostatic\"")})
add("lever_chain_slack_gravity_reversed", {"case.toml": sub(MAN, "gravity_m_s2 = [0.0, -9.80665, 0.0]", "gravity_m_s2 = [0.0, 9.80665, 0.0]")})
add("lever_chain_inconsistent_dimensions", {"case.toml": sub(MAN, "c_mm = 350.0", "c_mm = 50.0")})
# --- FE model
add("rigid_body_modes_left", {"case.toml": sub(FE, 'fixed = ["x", "y", "z"]', 'fixed = ["x"]')})
add("no_supports", {"case.toml": sub(FE, '[[support]]\nset = "bore_A0"\nfixed = ["x", "y", "z"]\n', "")})
add("support_set_not_in_mesh", {"case.toml": sub(FE, 'set = "bore_A0"', 'set = "bore_B"')})
add("factor_exceeds_memory_limit", {"case.toml": FE + "\n[solver]\nmax_factor_gb = 0.001\nmethod = \"direct\"\n"})
# --- meshes
add("msh_missing", {"case.toml": CUBE})
add("msh_empty", {"case.toml": CUBE, "cube.msh": ""})
add("msh_not_a_mesh", {"case.toml": CUBE, "cube.msh": "solid cube\nfacet normal 0 0 1\nendsolid\n"})
add("msh_truncated", {"case.toml": CUBE, "cube.msh": cube_msh(truncate="3 1 4 6")})
add("msh_corrupt_node_line", {"case.toml": CUBE, "cube.msh": cube_msh().replace("0.1 0.1 0.1", "0.1 zz 0.1")})
add("msh_inverted_tet", {"case.toml": CUBE, "cube.msh": cube_msh(inverted=True)})
add("msh_without_physical_groups", {"case.toml": CUBE, "cube.msh": cube_msh(groups=False)})
add("msh_element_refers_to_missing_node", {"case.toml": CUBE, "cube.msh": cube_msh(bad_node_ref=True)})
add("msh_nan_coordinate", {"case.toml": CUBE, "cube.msh": cube_msh(nan_coord=True)})
add("msh_surface_only", {"case.toml": CUBE, "cube.msh": cube_msh(volume=False)})
add("msh_duplicate_group_name", {"case.toml": CUBE, "cube.msh": cube_msh(dup_names=True)})
# --- files and output
add("case_file_missing", {}, args=["run", "nothere.toml", "-o", "@OUT@"])
add("case_path_is_directory", {"sub/.keep": ""}, args=["run", "sub", "-o", "@OUT@"])
add("output_dir_under_regular_file", {"case.toml": FE}, args=["run", "case.toml", "-o", "@FILE@/out"])
add("output_dir_in_proc", {"case.toml": FE}, args=["run", "case.toml", "-o", "/proc/kinetofem-out"])
add("disk_full_fe_static", {"case.toml": FE}, fsize=200000)
add("disk_full_manipulator", {"case.toml": MAN}, fsize=300000)

# --- linkage cases whose bodies carry FE parts ([[part]], [[face_set]], face keys)
E.update({'part_file_missing': 'case.toml:38: key \'part[0].file\' = "parts/crank.geo": no such file (parts/crank.geo)', 'part_file_corrupt_step': "part 'crank' (crank.step): crank.step: importing the shape failed: Could not read file 'crank.step'", 'part_file_open_surface_loop': "part 'crank' (block.geo): block.geo: meshing failed: No elements in volume 1", 'part_face_set_not_in_part': "part 'crank' (crank.geo): joint 'B' acts through face set 'bore_A', which the part does not have (it has: bore_B, bore_O)", 'part_face_set_is_curves': "part 'crank' (crank.geo): joint 'B' acts through 'bore_B', which is not a surface of the part (it is a curve or point group); surface sets: bore_O", 'part_unit_too_small_for_joints': "part 'crank' (crank.geo): the part spans 0.1456 mm in the plane but its load points 'O' and 'B' are 100 mm apart: is its length unit right? (expected a part of about 100 mm or more)", 'part_placed_off_its_bores': "part 'crank' (crank.geo): joint 'O' at (0.000, 0.000) mm (body frame) lies 40.0", 'part_twice_for_one_body': 'case.toml:42: key \'part[1].body\' = "crank": this body already has a part (one part per body)', 'part_lever_bore_wider_than_plate': "part 'crank' (lever): lever bore_diameter_m = 0.035 must be smaller than width_m = 0.03", 'part_msh_surface_only': "part 'crank' (crank.msh): crank.msh: the mesh has no volume elements", 'part_face_set_box_selects_nothing': "part 'crank' (crank.geo): face set 'pin_B' of crank.geo: no surface lies inside box [189.5, -10.5, -15.5, 210.5, 10.5, 15.5] mm; the part spans [-20, -20, -15, 120, 20, 15] mm", 'part_on_the_ground': 'case.toml:42: key \'part[1].body\' = "ground": a part of the ground (the frame) needs held_face, the face set of its foundation', 'part_drive_without_face': "case.toml:71: key 'force_drive[0].name': drive 'motor' acts on body 'crank', which has a part: give 'face_j' (a face set of the part)", 'part_face_key_on_body_without_part': "case.toml:62: key 'joint[2].face_j': body 'slider' has no [[part]] to act through", 'part_geo_without_length_unit': "part 'crank' (crank.geo): crank.geo: .geo files carry no length unit: give length_unit", 'part_step_unit_disagrees': "part 'crank' (crank.step): crank.step: length_unit = 1 m per file unit disagrees with the file's own unit, 0.001 m", 'part_dimension_of_other_source': 'case.toml:45: key \'part[0].roller_radius_mm\': not a dimension of a "lever" part', 'trapezoid_zero_accel_fraction_manipulator': "case.toml:19: key 'motion.accel_fraction' = 0 is out of range: must be >0 and <=1", 'negative_initial_step': "case.toml:91: key 'simulation.initial_step_s' = -0.001 s is out of range: must be >=0 and <=1e+07 s (a plausible time: up to about 4 months)", 'part_unit_too_large_for_mesh': "part 'crank' (crank.geo): crank.geo: the part spans 148.7 m, 7433 elements of 0.02 m across (at most 2000): is its length unit right, or the element size?"})
# Base: the slider-crank of cases/mechanisms/slider_crank, the crank an FE part
# (crank.geo, OpenCASCADE in mm, its bores named by physical surfaces), the rod
# and the slider rigid. Valid as it stands (checked by hand: it runs in ~1 s).
LINK = """[case]
name = "r"
type = "linkage"

[[body]]
name = "ground"
fixed = true

[[body]]
name = "crank"
pose_mm_deg = [0.0, 0.0, 30.0]

[[body]]
name = "rod"
mass_kg = 2.0
inertia_kgm2 = 1.5e-2
com_mm = [150.0, 0.0]
pose_mm_deg = [86.6025, 50.0, -9.594]

[[body]]
name = "slider"
mass_kg = 1.5
inertia_kgm2 = 1.0e-3
pose_mm_deg = [382.41, 0.0, 0.0]

[[point]]
body = "crank"
name = "pin"
at_mm = [100.0, 0.0]

[[point]]
body = "rod"
name = "end"
at_mm = [300.0, 0.0]

[[part]]
body = "crank"
file = "crank.geo"
length_unit = "mm"

[[joint]]
name = "O"
type = "revolute"
body_i = "ground"
body_j = "crank"
face_j = "bore_O"

[[joint]]
name = "B"
type = "revolute"
body_i = "crank"
point_i = "pin"
body_j = "rod"
face_i = "bore_B"

[[joint]]
name = "C"
type = "revolute"
body_i = "rod"
point_i = "end"
body_j = "slider"

[[joint]]
name = "guide"
type = "prismatic"
body_i = "ground"
body_j = "slider"
axis = [1.0, 0.0]

[[force_drive]]
name = "motor"
body_i = "ground"
body_j = "crank"
face_j = "bore_O"
law = "dc_motor"
stall_torque_nm = 20.0
no_load_speed_rpm = 300.0

[mesh]
element_size_mm = 20.0
order = 1

[material]
youngs_modulus_mpa = 210000.0
poisson_ratio = 0.3
density_kg_m3 = 7850.0

[simulation]
duration_s = 0.01
output_times = 3
"""

# The crank (mm): bore O at the origin, bore B at x = 100 mm, bosses 40 mm
# (bores 20 mm) x 30 mm, plate 25 x 12 mm. `bores` writes the Physical
# statements of the bores; `unit` scales the numbers (1e-3: the same crank in m).
def crank_geo(bores="surfaces", unit=1.0):
    L = ["// Crank of the slider-crank: bore O at the origin, bore B on +x.", 'SetFactory("OpenCASCADE");',
         f"s = {unit:g};", "length = 100*s; D = 40*s; d = 20*s; L = 30*s; w = 25*s; t = 12*s; e = 0.5*s;",
         "Cylinder(1) = {0, 0, -L/2, 0, 0, L, D/2};", "Cylinder(2) = {length, 0, -L/2, 0, 0, L, D/2};",
         "Box(3) = {0, -w/2, -t/2, length, w, t};", "BooleanUnion(4) = {Volume{1}; Delete;}{Volume{2, 3}; Delete;};",
         "Cylinder(5) = {0, 0, -L, 0, 0, 2*L, d/2};", "Cylinder(6) = {length, 0, -L, 0, 0, 2*L, d/2};",
         "BooleanDifference(7) = {Volume{4}; Delete;}{Volume{5, 6}; Delete;};"]
    box_O = "{-d/2-e, -d/2-e, -L/2-e, d/2+e, d/2+e, L/2+e}"
    box_B = "{length-d/2-e, -d/2-e, -L/2-e, length+d/2+e, d/2+e, L/2+e}"
    if bores in ("surfaces", "bore_B_curves"):
        L.append(f'Physical Surface("bore_O") = Surface In BoundingBox{box_O};')
    if bores == "surfaces":
        L.append(f'Physical Surface("bore_B") = Surface In BoundingBox{box_B};')
    if bores == "bore_B_curves":  # the bore's edge circles, where its surface was meant
        L.append(f'Physical Curve("bore_B") = Curve In BoundingBox{box_B};')
    if bores != "none":
        L.append('Physical Volume("crank") = {7};')
    return "\n".join(L) + "\n"

# A built-in-kernel block 100 x 20 x 10 mm whose surface loop lacks its top face.
OPEN_LOOP_GEO = """// A block 100 x 20 x 10 mm, built-in kernel: the surface loop lacks the top face.
Point(1) = {0, -10, -5}; Point(2) = {100, -10, -5}; Point(3) = {100, 10, -5}; Point(4) = {0, 10, -5};
Point(5) = {0, -10, 5}; Point(6) = {100, -10, 5}; Point(7) = {100, 10, 5}; Point(8) = {0, 10, 5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Line(9) = {1, 5}; Line(10) = {2, 6}; Line(11) = {3, 7}; Line(12) = {4, 8};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(3) = {1, 10, -5, -9}; Plane Surface(3) = {3};
Curve Loop(4) = {2, 11, -6, -10}; Plane Surface(4) = {4};
Curve Loop(5) = {3, 12, -7, -11}; Plane Surface(5) = {5};
Curve Loop(6) = {4, 9, -8, -12}; Plane Surface(6) = {6};
Surface Loop(1) = {1, 3, 4, 5, 6};
Volume(1) = {1};
"""

REPO = os.path.normpath(os.path.join(ROOT, "..", "..", ".."))
CRANK_STEP = open(os.path.join(REPO, "cases", "slider_crank_parts", "parts", "crank.step")).read()
# The crank.step's bores by box (in its mm), as in cases/slider_crank_parts.
STEP_FACE_SETS = """
[[face_set]]
body = "crank"
name = "bore_O"
box_mm = [-10.5, -10.5, -15.5, 10.5, 10.5, 15.5]

[[face_set]]
body = "crank"
name = "bore_B"
box_mm = [89.5, -10.5, -15.5, 110.5, 10.5, 15.5]
"""
def step_part(text, unit=None):
    return sub(text, 'file = "crank.geo"\nlength_unit = "mm"\n', 'file = "crank.step"\n' + (f'length_unit = "{unit}"\n' if unit else "")) + STEP_FACE_SETS

LEVER_PART = 'source = "lever"\nlength_mm = 100.0\nwidth_mm = 30.0\nthickness_mm = 12.0\nbore_diameter_mm = 20.0\nboss_diameter_mm = 40.0\nboss_length_mm = 30.0\nangle_deg = -90.0\n'
def lever_part(text):
    t = sub(text, 'file = "crank.geo"\nlength_unit = "mm"\n', LEVER_PART)
    return sub(sub(sub(t, 'face_j = "bore_O"', 'face_j = "bore_A0"'), 'face_i = "bore_B"', 'face_i = "bore_A"'), 'face_j = "bore_O"', 'face_j = "bore_A0"')

G = crank_geo()
add("part_file_missing", {"case.toml": sub(LINK, 'file = "crank.geo"', 'file = "parts/crank.geo"'), "crank.geo": G})
add("part_file_corrupt_step", {"case.toml": step_part(LINK), "crank.step": CRANK_STEP[: CRANK_STEP.index("#200 =")]})
add("part_file_open_surface_loop", {"case.toml": sub(LINK, 'file = "crank.geo"', 'file = "block.geo"'), "block.geo": OPEN_LOOP_GEO})
add("part_face_set_not_in_part", {"case.toml": sub(LINK, 'face_i = "bore_B"', 'face_i = "bore_A"'), "crank.geo": G})
add("part_face_set_is_curves", {"case.toml": LINK, "crank.geo": crank_geo(bores="bore_B_curves")})
add("part_unit_too_small_for_joints", {"case.toml": LINK, "crank.geo": crank_geo(unit=1e-3)})
add("part_placed_off_its_bores", {"case.toml": sub(LINK, 'length_unit = "mm"\n', 'length_unit = "mm"\noffset_mm = [0.0, 40.0]\n'), "crank.geo": G})
add("part_twice_for_one_body", {"case.toml": sub(LINK, "[[joint]]", '[[part]]\nbody = "crank"\nfile = "crank.geo"\nlength_unit = "mm"\n\n[[joint]]'), "crank.geo": G})
add("part_lever_bore_wider_than_plate", {"case.toml": sub(lever_part(LINK), "bore_diameter_mm = 20.0", "bore_diameter_mm = 35.0")})
add("part_msh_surface_only", {"case.toml": sub(sub(LINK, 'file = "crank.geo"\nlength_unit = "mm"', 'file = "crank.msh"\nlength_unit = "m"'), 'face_i = "bore_B"', 'face_i = "loaded"').replace('face_j = "bore_O"', 'face_j = "fixed"'), "crank.msh": cube_msh(volume=False)})
add("part_face_set_box_selects_nothing", {"case.toml": sub(sub(LINK, 'face_i = "bore_B"', 'face_i = "pin_B"'), "[[joint]]", '[[face_set]]\nbody = "crank"\nname = "pin_B"\nbox_mm = [189.5, -10.5, -15.5, 210.5, 10.5, 15.5]\n\n[[joint]]'), "crank.geo": G})
add("part_on_the_ground", {"case.toml": sub(LINK, "[[joint]]", '[[part]]\nbody = "ground"\nfile = "crank.geo"\nlength_unit = "mm"\n\n[[joint]]'), "crank.geo": G})
add("part_drive_without_face", {"case.toml": sub(LINK, 'body_j = "crank"\nface_j = "bore_O"\nlaw', 'body_j = "crank"\nlaw'), "crank.geo": G})
add("part_face_key_on_body_without_part", {"case.toml": sub(LINK, 'body_j = "slider"\n\n', 'body_j = "slider"\nface_j = "bore_C"\n\n'), "crank.geo": G})
add("part_geo_without_length_unit", {"case.toml": sub(LINK, 'length_unit = "mm"\n', ""), "crank.geo": G})
add("part_step_unit_disagrees", {"case.toml": step_part(LINK, unit="m"), "crank.step": CRANK_STEP})
add("part_dimension_of_other_source", {"case.toml": sub(lever_part(LINK), "boss_length_mm = 30.0\n", "boss_length_mm = 30.0\nroller_radius_mm = 75.0\n")})
add("trapezoid_zero_accel_fraction_manipulator", {"case.toml": sub(MAN, 'law = "polynomial345"', 'law = "trapezoidal"\naccel_fraction = 0.0')})
add("negative_initial_step", {"case.toml": sub(LINK, "output_times = 3", "output_times = 3\ninitial_step_s = -1.0e-3"), "crank.geo": G})
add("part_unit_too_large_for_mesh", {"case.toml": sub(LINK, 'length_unit = "mm"', 'length_unit = "m"'), "crank.geo": G})

# --- the elastic assembly (issue 12): [assembly] keys of both case types, the
# stiffness keys of a linkage's chains and drives, [[assembly_point]], and
# linkages the elastic model cannot hold. The manipulator base MAN runs the
# assembly by default (assembly.enabled = true).
def man_assembly(keys, base=MAN):
    return base + "\n[assembly]\n" + keys + "\n"
LEVER_MAN = sub(sub(MAN, 'type = "lever_chain"', 'type = "lever"'), "stroke_deg = 80.0", "stroke_deg = 30.0")
# The lever-chain manipulator of cases/mechanisms/lever_chain_linkage as a
# linkage with the manipulator's parametric parts (lever, arm_with_roller: the
# face sets of pipeline/manipulator_preset.cpp), the face keys on every joint,
# drive and point mass, the assembly on; 11 output times (the kinematic check before meshing
# assembles pose after pose: 3 output times, 40 deg apart, are too far apart). Valid as it
# stands (checked by hand: it runs in about 1 s).
CHAIN = """[case]
name = "r"
type = "linkage"

[[body]]
name = "frame"
fixed = true

[[body]]
name = "lever"
mass_kg = 10.66
inertia_kgm2 = 0.359
com_mm = [0.0, 250.0]

[[body]]
name = "arm"
mass_kg = 10.94
inertia_kgm2 = 0.253
com_mm = [-146.1, 8.8]
pose_mm_deg = [0.0, 500.0, 0.0]

[[point]]
body = "frame"
name = "B0"
at_mm = [75.0, 88.23529411764706]

[[point]]
body = "lever"
name = "A"
at_mm = [0.0, 500.0]

[[point]]
body = "arm"
name = "H"
at_mm = [-350.0, 100.0]

[[part]]
body = "lever"
source = "lever"

[[part]]
body = "arm"
source = "arm_with_roller"

[[point_mass]]
body = "arm"
name = "gripper"
mass_kg = 20.0
at_point = "H"
face = "gripper_mount"

[[joint]]
name = "A0"
type = "revolute"
body_i = "frame"
body_j = "lever"
face_j = "bore_A0"

[[joint]]
name = "A"
type = "revolute"
body_i = "lever"
point_i = "A"
body_j = "arm"
face_i = "bore_A"
face_j = "bore_A"

[[joint]]
name = "chain"
type = "chain"
body_i = "frame"
point_i = "B0"
body_j = "arm"
radius_mm = 75.0
wrap = "ccw"
face_j = "roller_rim"
ea_per_strand_n = 5.0e6

[[motion_drive]]
name = "lever_drive"
coordinate = "angle"
body_i = "frame"
body_j = "lever"
face_j = "bore_A0"
law = "polynomial345"
stroke_deg = 80.0
duration_s = 2.0

[[assembly_point]]
name = "H"
body = "arm"
point = "H"
face = "gripper_mount"

[assembly]
enabled = true

[mesh]
element_size_mm = 20.0
order = 1

[simulation]
duration_s = 2.0
output_times = 11
"""
# A crank (a "lever" part, bores bore_A0 at the origin and bore_A on +x) on a
# pin O, turned by a DC motor: nothing but a torque holds its rotation. Valid
# with assembly.enabled = false (checked by hand).
FREE_CRANK = """[case]
name = "r"
type = "linkage"

[[body]]
name = "ground"
fixed = true

[[body]]
name = "crank"

[[part]]
body = "crank"
""" + LEVER_PART + """
[[joint]]
name = "O"
type = "revolute"
body_i = "ground"
body_j = "crank"
face_j = "bore_A0"

[[force_drive]]
name = "motor"
body_i = "ground"
body_j = "crank"
face_j = "bore_A0"
law = "dc_motor"
stall_torque_nm = 20.0
no_load_speed_rpm = 300.0

[assembly]
enabled = true

[mesh]
element_size_mm = 20.0
order = 1

[simulation]
duration_s = 0.01
output_times = 3
"""
# The rigid lever-chain linkage (no parts), as cases/mechanisms/lever_chain_linkage.
CHAIN_RIGID = sub(sub(CHAIN, '[[part]]\nbody = "lever"\nsource = "lever"\n\n[[part]]\nbody = "arm"\nsource = "arm_with_roller"\n\n', ""), '[[assembly_point]]\nname = "H"\nbody = "arm"\npoint = "H"\nface = "gripper_mount"\n\n', "")
for face in ('face_j = "bore_A0"\n', 'face_i = "bore_A"\n', 'face_j = "bore_A"\n', 'face_j = "roller_rim"\n', 'face = "gripper_mount"\n'):
    CHAIN_RIGID = CHAIN_RIGID.replace(face, "")

E.update({'assembly_chain_ea_zero_manipulator': "case.toml:31: key 'assembly.chain_ea_per_strand_n' = 0 N is out of range: must be >0 and <=1e+12 N (a plausible axial stiffness EA)", 'assembly_chain_ea_negative_manipulator': "case.toml:31: key 'assembly.chain_ea_per_strand_n' = -5e+06 N is out of range: must be >0 and <=1e+12 N (a plausible axial stiffness EA)", 'assembly_chain_ea_inf_manipulator': "case.toml:31: key 'assembly.chain_ea_per_strand_n' = inf is not a finite number", 'assembly_chain_ea_nan_manipulator': "case.toml:31: key 'assembly.chain_ea_per_strand_n' = nan is not a finite number", 'assembly_chain_strands_zero_manipulator': "case.toml:31: key 'assembly.chain_strands' = 0 is out of range: must be >=1 and <=3", 'assembly_drive_stiffness_zero_manipulator': "case.toml:31: key 'assembly.drive_stiffness_n_m_per_rad' = 0 N*m/rad is out of range: must be >0 and <=1e+12 N*m/rad (a plausible stiffness)", 'assembly_drive_stiffness_inf_manipulator': "case.toml:31: key 'assembly.drive_stiffness_n_m_per_rad' = inf is not a finite number", 'assembly_coupling_unknown_manipulator': 'case.toml:31: key \'assembly.coupling\' = "rigid" is not allowed: use one of "distributing", "rigid_bore"', 'assembly_chain_keys_on_lever_manipulator': 'case.toml:31: key \'assembly.chain_ea_per_strand_n\': the lever manipulator has no chain (this key is for mechanism.type = "lever_chain")', 'assembly_linkage_without_parts': "case.toml:76: key 'assembly.enabled' = true, but no body has a [[part]]: the elastic assembly needs at least one FE part", 'assembly_chain_without_ea': "case.toml:69: key 'joint[2].name': chain 'chain' needs ea_per_strand_n (its axial stiffness EA, N) for the elastic assembly", 'assembly_ea_on_revolute_joint': "case.toml:66: key 'joint[1].ea_per_strand_n': only a chain joint has an axial stiffness (this joint is revolute)", 'assembly_drive_stiffness_without_assembly': "case.toml:87: key 'motion_drive[0].stiffness_n_m_per_rad': set assembly.enabled = true to use it (the drive's stiffness only enters the elastic assembly)", 'assembly_point_on_part_without_face': 'case.toml:90: key \'assembly_point[0].name\': point \'H\' is on body \'arm\', which has a part: name the face set that carries it (face = "...")', 'assembly_point_on_unknown_body': 'case.toml:91: key \'assembly_point[0].body\' = "gripper": no moving body of that name (moving bodies: lever, arm)', 'assembly_slide_on_rigid_guide': 'case.toml:83: key \'slide[0].joint\' = "guide": its guide (body_i \'ground\') has no part: a [[slide]] is for an elastic guide', 'assembly_crank_held_by_motor_torque': "case.toml: the elastic assembly cannot be solved or written: elastic assembly at t = 0 s: the structure is a mechanism (rank 22 of 23 unknowns): nothing holds the rotation about z at joint 'O' (between 'ground' and 'crank'; force drive 'motor' applies a torque there but holds no angle); hold it by a motion drive (rigid or with a stiffness), a chain or another joint", 'assembly_displacement_drive_torsional_stiffness': "case.toml:82: key 'motion_drive[0].stiffness_n_m_per_rad': drive 'lever_drive' drives a displacement: its stiffness is stiffness_n_per_m (N/m)"})
add("assembly_chain_ea_zero_manipulator", {"case.toml": man_assembly("chain_ea_per_strand_n = 0.0")})
add("assembly_chain_ea_negative_manipulator", {"case.toml": man_assembly("chain_ea_per_strand_n = -5.0e6")})
add("assembly_chain_ea_inf_manipulator", {"case.toml": man_assembly("chain_ea_per_strand_n = inf")})
add("assembly_chain_ea_nan_manipulator", {"case.toml": man_assembly("chain_ea_per_strand_n = nan")})
add("assembly_chain_strands_zero_manipulator", {"case.toml": man_assembly("chain_strands = 0")})
add("assembly_drive_stiffness_zero_manipulator", {"case.toml": man_assembly("drive_stiffness_n_m_per_rad = 0.0")})
add("assembly_drive_stiffness_inf_manipulator", {"case.toml": man_assembly("drive_stiffness_n_m_per_rad = inf")})
add("assembly_coupling_unknown_manipulator", {"case.toml": man_assembly('coupling = "rigid"')})
add("assembly_chain_keys_on_lever_manipulator", {"case.toml": man_assembly("chain_ea_per_strand_n = 1.0e7", LEVER_MAN)})
add("assembly_linkage_without_parts", {"case.toml": CHAIN_RIGID})
add("assembly_chain_without_ea", {"case.toml": sub(CHAIN, "ea_per_strand_n = 5.0e6\n", "")})
add("assembly_ea_on_revolute_joint", {"case.toml": sub(CHAIN, 'face_i = "bore_A"\n', 'face_i = "bore_A"\nea_per_strand_n = 5.0e6\n')})
add("assembly_drive_stiffness_without_assembly", {"case.toml": sub(sub(CHAIN, "ea_per_strand_n = 5.0e6\n", ""), "[assembly]\nenabled = true\n", "[assembly]\nenabled = false\n").replace('[[assembly_point]]\nname = "H"\nbody = "arm"\npoint = "H"\nface = "gripper_mount"\n\n', "").replace('duration_s = 2.0\n\n', 'duration_s = 2.0\nstiffness_n_m_per_rad = 1.0e5\n\n', 1)})
add("assembly_point_on_part_without_face", {"case.toml": sub(CHAIN, 'body = "arm"\npoint = "H"\nface = "gripper_mount"\n', 'body = "arm"\npoint = "H"\n')})
add("assembly_point_on_unknown_body", {"case.toml": sub(CHAIN, 'name = "H"\nbody = "arm"\npoint = "H"', 'name = "H"\nbody = "gripper"\npoint = "H"')})
add("assembly_slide_on_rigid_guide", {"case.toml": sub(LINK, "[mesh]", "[assembly]\nenabled = true\n\n[[slide]]\njoint = \"guide\"\ncontact_length_mm = 20.0\n\n[mesh]"), "crank.geo": G})
add("assembly_crank_held_by_motor_torque", {"case.toml": FREE_CRANK})
# The lever, rigid, driven by the x displacement of its pin A (0 to -300 mm: it turns 36.9 deg ccw).
RIGID_LEVER = sub(sub(CHAIN, '[[part]]\nbody = "lever"\nsource = "lever"\n\n', ""), 'face_i = "bore_A"\n', "").replace('body_j = "lever"\nface_j = "bore_A0"\n', 'body_j = "lever"\n')
add("assembly_displacement_drive_torsional_stiffness", {"case.toml": sub(sub(sub(RIGID_LEVER, 'coordinate = "angle"\nbody_i = "frame"\nbody_j = "lever"\n', 'coordinate = "displacement"\nbody_i = "frame"\nbody_j = "lever"\npoint_j = "A"\n'), "stroke_deg = 80.0", "stroke_mm = -300.0"), "stroke_mm = -300.0\nduration_s = 2.0\n", "stroke_mm = -300.0\nduration_s = 2.0\nstiffness_n_m_per_rad = 1.0e5\n")})

# --- issue 13: unit-load superposition and field output times
E.update({
    "field_times_outside_the_motion": "case.toml:31: key 'output.field_times_s': 5 s is outside the motion [0, 2] s",
    "field_times_not_numbers": "case.toml:31: key 'output.field_times_s': every element must be a time in s",
    "superposition_with_bearing_pressure": "link 'lever': unit-load superposition was asked for, but a joint's cosine bearing pressure is not a combination of fixed load patterns",
    "manipulator_factor_exceeds_memory_limit": "more than the 0.0001 GB allowed: coarsen the mesh or raise the limit",
})
add("field_times_outside_the_motion", {"case.toml": MAN + "\n[output]\nfield_times_s = [0.5, 5.0]\n"})
add("field_times_not_numbers", {"case.toml": MAN + "\n[output]\nfield_times_s = [\"end\"]\n"})
add("superposition_with_bearing_pressure", {"case.toml": MAN + "\n[loads]\nbore_load = \"bearing\"\n\n[solver]\nload_path = \"superposition\"\n"})
add("manipulator_factor_exceeds_memory_limit", {"case.toml": MAN + "\n[solver]\nmethod = \"direct\"\nmax_factor_gb = 0.0001\n"})

VALID = {"valid_cube": {"case.toml": CUBE, "cube.msh": cube_msh()}}

os.makedirs(ROOT, exist_ok=True)
for k, (name, files, expected, extra) in enumerate(cases, start=1):
    d = os.path.join(ROOT, f"{k:02d}_{name}")
    os.makedirs(d, exist_ok=True)
    for fn, text in files.items():
        p = os.path.join(d, fn); os.makedirs(os.path.dirname(p), exist_ok=True)
        with open(p, "w", encoding="utf-8", errors="surrogateescape") as f: f.write(text)
    open(os.path.join(d, "expected.txt"), "w").write(expected + "\n")
    if "args" in extra:
        open(os.path.join(d, "args.txt"), "w").write("\n".join(extra["args"]) + "\n")
    if "fsize" in extra:
        open(os.path.join(d, "fsize_limit_bytes.txt"), "w").write(f"{extra['fsize']}\n")
for name, files in VALID.items():
    d = os.path.join(ROOT, name); os.makedirs(d, exist_ok=True)
    for fn, text in files.items(): open(os.path.join(d, fn), "w").write(text)
print(len(cases), "cases")
