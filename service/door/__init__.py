"""The door: text becomes a validated study (parse the text within its budget, validate it
once against the study model, resolve what the types leave open and expand it); the study
model's JSON Schema is the body schema the OpenAPI document serves."""
