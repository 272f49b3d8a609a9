// The crank of another folder: outside this case folder.
Include "../65_part_face_set_not_in_part/crank.geo";
