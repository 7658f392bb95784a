"""The project's pipeline as one command (hideseek_pipeline, `cli`): one run's steps (`train`,
`evaluate`, `analyze`, through a `workspace`) and the sweep's queue (`sweep_config` reads its
phases, `queue` holds its state and order, `runner` trains it, `control` reports on and steers it),
recording into the run registry of a checkout (`records`).
"""
