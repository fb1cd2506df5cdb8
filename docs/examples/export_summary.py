import polars as pl

particles = pl.read_parquet("export/particles.parquet")
contacts = pl.read_parquet("export/contacts.parquet")
print(particles.group_by("material").agg(pl.len(), pl.col("speed_m_s").mean()).sort("material"))
print("mean normal force:", contacts["normal_force_n"].mean(), "N")
