"""What a study keeps: the Parquet store, the Arrow column schemas, reading rows back."""
