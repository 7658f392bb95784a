"""The run registry (policies/policies.yaml) and run folders (docs/runs/<run>/) of the checkout that
receives the sweep's records. The registry's reader and writer are hideseek_analysis's registry
module, found in that checkout: a trainer pinned at an older commit writes today's registry with
today's reader, which knows every field the registry holds now."""
import importlib.util
import os
import shutil



def load_registry_module(root):
    """The registry module of the checkout at `root` (not the one on the Python path: the queue's
    records follow the checkout that holds them)."""
    path = os.path.join(root, "src", "hideseek_analysis", "python", "hideseek_analysis", "registry.py")
    spec = importlib.util.spec_from_file_location("hideseek_registry", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class Records:
    def __init__(self, root, code_root, given_by="SWEEP_RECORD_ROOT"):
        """`root`: the checkout that receives the records (its registry says which runs are done);
        `code_root`: the checkout whose registry module and variants are read where `root` has
        none (a bare folder of records); `given_by`: what named `root`, for the error."""
        self.root = root
        self.registry_path = os.path.join(root, "policies", "policies.yaml")
        if not os.path.isfile(self.registry_path):
            raise FileNotFoundError("%s: no policies/policies.yaml in %s (records go into a registry there: an "
                                    "empty policies/policies.yaml starts one)" % (given_by, root))
        own = os.path.isfile(os.path.join(root, "src", "hideseek_analysis", "python", "hideseek_analysis", "registry.py"))
        self.registry = load_registry_module(root if own else code_root)
        # The note the queue records on each run it trained: the registry's, which Table 2, the
        # claims and the median to ship look for, and where the run's phases are listed.
        self.note = self.registry.SWEEP_NOTE + " (config/sweep.yaml)"

    def entries(self):
        """The registry's runs, read again only when the file has changed (the queue asks for every
        run's state every few seconds)."""
        st = os.stat(self.registry_path)
        key = (st.st_mtime_ns, st.st_size, st.st_ino)
        if key != getattr(self, "_key", None):
            self._entries, self._key = self.registry.runs(self.registry_path), key
        return self._entries

    def entry(self, name):
        return self.entries().get(name)

    def docs(self, name, *parts):
        return os.path.join(self.root, "docs", "runs", name, *parts)

    def partial(self, name):
        """An unfinished run's records (`sweep partial`): its training log and curve so far."""
        return self.docs(name, "partial")

    def clear_partial(self, name):
        """Removes a run's partial records, once it is recorded whole; whether there were any."""
        if not os.path.isdir(self.partial(name)):
            return False
        shutil.rmtree(self.partial(name))
        return True

    def recorded_steps(self, name):
        """The steps the registry records for a sweep run (its note, which the queue writes last);
        0 for a run of that name that another command trained: the queue trains it again."""
        e = self.entry(name)
        if not e or not str(e.get("note", "")).startswith(self.note):
            return 0
        return int(e.get("steps", 0))

    def is_done(self, run):
        """Recorded as a sweep run with all its steps, both evaluations and its trajectories (a
        seeker's run: its seeker evaluation; a self-play: its selfplay.md, which its record writes
        last)."""
        if run.phase.role == "selfplay":
            return _nonempty(self.docs(run.name, "selfplay.md"))
        if run.phase.role != "hider":
            return (self.recorded_steps(run.name) >= run.phase.steps
                    and _nonempty(self.docs(run.name, "seeker_evaluation.csv")))
        return (self.recorded_steps(run.name) >= run.phase.steps and _nonempty(self.docs(run.name, "evaluation.csv"))
                and _nonempty(self.docs(run.name, "sampled", "evaluation.csv"))
                and _nonempty(self.docs(run.name, "trajectories.png")))

    def analysed(self, name):
        return _nonempty(self.docs(name, "analysis", "behaviour.csv"))

    def has_tsne(self, name):
        return _nonempty(self.docs(name, "analysis", "tsne_neighbours.csv"))

    def has_memoryless(self, name):
        return _nonempty(self.docs(name, "analysis", "memoryless", "behaviour.csv"))

    def seeker_evaluation(self, name):
        """A seeker's run: its capture rate and the scripted seeker's against its opponent (the
        table's first hider)."""
        with open(self.docs(name, "seeker_evaluation.csv")) as f:
            rows = [line.split(",") for line in f.read().strip().splitlines()[1:]]
        rate = {r[1]: r[4] for r in rows if r[0] == rows[0][0]}
        return "captures %s: learned %s, scripted %s" % (rows[0][0], rate.get("learned", "?"), rate.get("scripted", "?"))

    def evaluation(self, name, sub=""):
        """'living/success' of the evaluation's last row."""
        with open(self.docs(name, sub, "evaluation.csv")) as f:
            last = f.read().strip().splitlines()[-1].split(",")
        return "%s/%s" % (last[3], last[4])


def _nonempty(path):
    return os.path.isfile(path) and os.path.getsize(path) > 0
