// superdex_peer_mujoco_urdf: a URDF robot swinging freely in MuJoCo (which compiles URDF), its
// joint angles sampled every `--every` seconds, for the arm comparison (arm_peers.py).
//   superdex_peer_mujoco_urdf --urdf FILE --dt DT --duration S [--every S] [--integrator euler|rk4]
// Prints one JSON line: wall_seconds (the stepping calls), simulated_seconds, samples
// [[t, q_1, ..., q_n], ...], settings.
#include <mujoco/mujoco.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  std::string urdf, integrator = "rk4";
  double dt = 1e-3, duration = 2.0, every = 0.01;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--urdf") urdf = v;
    else if (k == "--dt") dt = std::stod(v);
    else if (k == "--duration") duration = std::stod(v);
    else if (k == "--every") every = std::stod(v);
    else if (k == "--integrator") integrator = v;
    else {
      std::fprintf(stderr, "unknown option %s\n", k.c_str());
      return 2;
    }
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML(urdf.c_str(), nullptr, error, sizeof error);
  if (!m) {
    std::printf("{\"failed\": true, \"failure\": \"%s\"}\n", error);
    return 1;
  }
  m->opt.timestep = dt;
  m->opt.gravity[0] = 0;
  m->opt.gravity[1] = 0;
  m->opt.gravity[2] = -9.81;
  m->opt.integrator = integrator == "euler" ? mjINT_EULER : mjINT_RK4;
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  const int steps = static_cast<int>(std::lround(duration / dt));
  const int stride = std::max(1, static_cast<int>(std::lround(every / dt)));
  std::vector<std::vector<double>> samples;
  auto sample = [&](double t) {
    std::vector<double> row{t};
    for (int j = 0; j < m->nq; ++j) row.push_back(d->qpos[j]);
    samples.push_back(row);
  };
  sample(0.0);
  double wall = 0.0;
  for (int s = 1; s <= steps; ++s) {
    const auto t0 = std::chrono::steady_clock::now();
    mj_step(m, d);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (s % stride == 0) sample(s * dt);
  }
  std::printf("{\"wall_seconds\": %.9g, \"simulated_seconds\": %.9g, \"nq\": %d, "
              "\"settings\": {\"dt\": %g, \"integrator\": \"%s\"}, \"samples\": [",
              wall, steps * dt, m->nq, dt, integrator.c_str());
  for (size_t i = 0; i < samples.size(); ++i) {
    std::printf(i ? ", [" : "[");
    for (size_t j = 0; j < samples[i].size(); ++j)
      std::printf(j ? ", %.17g" : "%.17g", samples[i][j]);
    std::printf("]");
  }
  std::printf("]}\n");
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
