// fuzzylite 6 as the oracle of `fuzzypid export-rules`: loads the exported rule file with
// fuzzylite's own importer and evaluates it on every row of the --surface CSV written from the
// same controller, at x = Ke e and y = Kec ec. Each output dK must give the row's ratio, 1 + dK, to
// 1e-9 (relative above 1). Exit 0 when every row agrees, else 1 with the worst row.
// Usage: fuzzylite_surface RULE_FILE(.fll|.fcl|.fis) SURFACE.csv KE KEC
#include <fl/Headers.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: fuzzylite_surface RULE_FILE SURFACE.csv KE KEC\n");
    return 2;
  }
  const std::string rule_file = argv[1];
  const double ke = std::strtod(argv[3], nullptr);
  const double kec = std::strtod(argv[4], nullptr);
  std::ifstream in(rule_file);
  std::stringstream text;
  text << in.rdbuf();
  fl::fuzzylite::setMachEps(0.0);  // else fuzzylite snaps degrees within 1e-6 of 0 or 1
  const std::string ext = rule_file.substr(rule_file.size() >= 4 ? rule_file.size() - 4 : 0);
  std::unique_ptr<fl::Engine> engine(ext == ".fll"   ? fl::FllImporter().fromString(text.str())
                                     : ext == ".fcl" ? fl::FclImporter().fromString(text.str())
                                                     : fl::FisImporter().fromString(text.str()));
  std::string status;
  if (!engine || !engine->isReady(&status)) {
    std::fprintf(stderr, "fuzzylite_surface: %s does not load: %s\n", rule_file.c_str(),
                 status.c_str());
    return 1;
  }
  fl::InputVariable* e = engine->getInputVariable("e");
  fl::InputVariable* ec = engine->getInputVariable("ec");
  fl::OutputVariable* out[3] = {engine->getOutputVariable("dKp"), engine->getOutputVariable("dKi"),
                                engine->getOutputVariable("dKd")};

  std::ifstream csv(argv[2]);
  std::string line;
  std::getline(csv, line);  // header: e_rad,ec_rad_s,kp_ratio,ki_ratio,kd_ratio
  long rows = 0;
  double worst = 0.0;
  std::string worst_row;
  while (std::getline(csv, line)) {
    double v[5];
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4]) != 5) {
      std::fprintf(stderr, "fuzzylite_surface: bad row: %s\n", line.c_str());
      return 1;
    }
    e->setValue(v[0] * ke);
    ec->setValue(v[1] * kec);
    engine->process();
    for (int g = 0; g < 3; ++g) {
      const double ratio = 1.0 + out[g]->getValue();
      const double d = std::fabs(ratio - v[2 + g]) / std::fmax(1.0, std::fabs(v[2 + g]));
      if (std::isnan(d) || d > worst) {
        worst = std::isnan(d) ? INFINITY : d;
        worst_row = line;
      }
    }
    ++rows;
  }
  std::printf("%s: %ld rows, max |fuzzylite - export-rules surface| %.3g\n", rule_file.c_str(),
              rows, worst);
  if (rows < 9 || !(worst <= 1e-9)) {
    std::fprintf(stderr, "fuzzylite_surface: worst row %s\n", worst_row.c_str());
    return 1;
  }
  return 0;
}
