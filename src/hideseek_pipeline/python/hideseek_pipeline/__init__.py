"""The project's pipeline as one command (hideseek_pipeline): the sweep's queue of training runs.

Modules: `sweep_config` reads config/sweep.yaml's phases, `queue` orders and runs them,
`processes` holds the process-tree, lock and port helpers, `records` reads and writes the run
registry of the checkout that receives the records.
"""
