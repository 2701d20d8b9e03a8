"""Ground motions as numbers: intensity measures of a motion, synthetic motions for a scenario."""
