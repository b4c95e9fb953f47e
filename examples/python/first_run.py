import matplotlib; matplotlib.use("Agg")  # plots to files, no window
import matplotlib.pyplot as plt
import blockdem

model = blockdem.load("examples/models/wall_window.json")  # or blockdem.generate.wall(...), or your own Model
result = blockdem.run(model, out="wall_run", levels=[100], window=(2, 4), rest=0.5)  # settle, then shake
h = result.history(100)  # numpy arrays: time (s), top_uy (m, relative to the table), top_ay (m/s^2), ...
plt.plot(h["time"], 1e3 * h["top_uy"]); plt.xlabel("time [s]"); plt.ylabel("top of the wall, out of plane [mm]")
plt.savefig("wall_run/top_uy.png")
print(result.level(100)["peaks"]["top_uy"], "->", "wall_run/top_uy.png")
