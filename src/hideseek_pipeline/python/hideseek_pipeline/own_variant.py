"""A variant file of one's own (`train --variant-config FILE`), as a run records it: the file, and
the sha256 of it and of its map, in the run's registry entry and beside its checkpoint. The run's
evaluation and analysis play that file, once both still hash as they did when it trained; a
checkpoint is not resumed on another version of either."""
import hashlib
import os

import yaml

from hideseek_pipeline.workspace import ToolError


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def check_file(path, variant, project_variants, step):
    """The file's absolute path, once it is a variant file named `variant` that is not one of the
    project's variants (whose runs Table 2 and the registry's shipping count); ToolError naming
    what is wrong otherwise."""
    if not os.path.isfile(path):
        raise ToolError("%s: --variant-config: no file %s" % (step, path))
    try:
        with open(path) as f:
            named = (yaml.safe_load(f) or {}).get("variant")
    except (yaml.YAMLError, AttributeError) as e:
        raise ToolError("%s: --variant-config: %s is not a variant file (a YAML mapping): %s" % (step, path, e))
    if named != variant:
        raise ToolError("%s: --variant-config: %s is variant '%s' (its variant field), not '%s': give the variant on "
                        "the command line as the file names it, or change the file's variant field"
                        % (step, path, named, variant))
    if variant in project_variants:
        raise ToolError("%s: --variant-config: '%s' is a variant of the project (config/variants/%s.yaml): a variant "
                        "file of one's own takes a name of its own, so that its runs are never counted as the "
                        "project's" % (step, variant, variant))
    return os.path.realpath(path)


def fingerprint(ws, variant, game, path):
    """The registry fields of a run trained on the variant file `path` (absolute) in `game`."""
    map_file = ws.resolve(variant, "map_file", game, path)
    return {"variant_config": path, "variant_sha256": sha256(path), "map_file": map_file,
            "map_sha256": sha256(map_file)}


def check_unchanged(ws, name, entry, step):
    """The variant file a recorded run trained on (None for a variant of the project), once it and
    the map it names here hash as the registry recorded; ToolError naming the file that changed
    otherwise. The map is the one this workspace resolves (a relative map name resolves under the
    workspace's config/), checked by content, not by path. An entry that records no sha256 (a
    self-play's generation, which names the file it plays now) is taken as it is."""
    path = entry.get("variant_config")
    if not path or "variant_sha256" not in entry:
        return path or None
    if not os.path.isfile(path):
        raise ToolError("%s: %s trained on %s, which is gone" % (step, name, path))
    now = fingerprint(ws, entry["variant"], entry["game"], path)
    for field, sha in (("variant_config", "variant_sha256"), ("map_file", "map_sha256")):
        if now[sha] != entry[sha]:
            raise ToolError("%s: %s trained on %s with sha256 %s; it has changed since (%s, sha256 %s), so %s would "
                            "play another game: restore the file, or train a run of its own on it"
                            % (step, name, entry[field], entry[sha], now[field], now[sha], step))
    return path


def check_resume(run_dir, fields, name, step):
    """A checkpoint is resumed on the variant file and map it trained on: `run_dir`/variant_files.yaml
    holds their fingerprint (none for a variant of the project), written whenever the run starts
    with no checkpoint yet, so that a run cut off before its first one starts again on the files
    given now."""
    saved_path = os.path.join(run_dir, "variant_files.yaml")
    if not os.path.isfile(os.path.join(run_dir, "checkpoint.pt")):
        # Nothing trained yet: the run starts (again) on the files given now.
        if fields:
            with open(saved_path, "w") as f:
                yaml.safe_dump(fields, f, sort_keys=False)
        elif os.path.exists(saved_path):
            os.remove(saved_path)
        return
    saved = None
    if os.path.isfile(saved_path):
        with open(saved_path) as f:
            saved = yaml.safe_load(f) or None
    was = saved and (saved.get("variant_sha256"), saved.get("map_sha256"))
    now = fields and (fields["variant_sha256"], fields["map_sha256"])
    if was != now:
        def said(f):
            return "the variant file %s (sha256 %s) and map %s (sha256 %s)" % (
                f["variant_config"], f["variant_sha256"], f["map_file"], f["map_sha256"]) if f else \
                "the project's variant files"
        raise ToolError("%s: %s's checkpoint in %s trained on %s; this run plays %s: name the run otherwise, or "
                        "restore the file" % (step, name, run_dir, said(saved), said(fields)))
