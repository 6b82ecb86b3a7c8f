"""What the table scripts read from rtfpga's printed output (imported by scripts/*.sh)."""

# The thesis scenes' directory names, as the tables name them.
SCENE_NAMES = {
    "Simple_plane_scene": "Simple plane",
    "Simple_plane2_scene": "Simple plane 2",
    "Glasses_scene": "Glasses",
    "Glasses_point_scene": "Glasses point",
    "Glass_pen_scene": "Glass pen",
    "Utah_teapot_scene": "Utah teapot",
    "All_materials_scene": "All materials",
}


def parse(lines):
    """The key=value tokens of `lines` (a key's first value wins) and the rows of the
    `| term | seconds |` table `rtfpga project` prints, as `term_<term>` keys (term_ARM,
    term_accelerator)."""
    kv = {}
    for line in lines:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if line.lstrip().startswith("|") and len(cells) == 2:
            kv.setdefault("term_" + cells[0], cells[1])
        for tok in line.split():
            if "=" in tok:
                k, v = tok.split("=", 1)
                kv.setdefault(k, v)
    return kv


def scene_name(directory):
    return SCENE_NAMES.get(directory, directory)
