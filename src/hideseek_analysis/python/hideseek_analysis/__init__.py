"""What the hider learned, and the paper's claims decided on the sweep's runs: the analysis as a
library. Each module does one thing; the scripts in ../../scripts are its command lines.

- registry: the variants (config/variants) and the run registry (policies/policies.yaml);
- config: the lists the analysis works through (paper_reference.yaml, sweep.yaml, the variants);
- runs: which runs count, and what each left in docs/runs/<run>/;
- stats: the bootstrap across training seeds (rliable's method) and its estimates;
- states: probes, state frequencies and transitions of one run's rollouts;
- tables: Table 3, the behaviour table, and the formatting every table shares;
- table2: Table 2 with its intervals, the paper's orderings and the two readings;
- figures: Figures 4-7 and the t-SNE across seeds, the performance profile;
- claims: every claim of the paper decided, with its effect size and interval.
"""
