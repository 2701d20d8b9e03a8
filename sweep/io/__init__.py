"""Input and output: files, units, schemas, records, problems and atomic writes.

YAML files, units, the scene, study and bodies schemas, ground-motion records, the problem
formatter every file check reports through, and atomic writes."""
