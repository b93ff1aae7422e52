"""The door: text becomes a validated study (parse the text, check it against the study
schema, resolve it into a study ready to expand)."""
