// examples/eval_motion.cpp: read a motion file and print where the moving origin is at
// eleven parameters, with the Plucker residual of the whole motion.
#include <iostream>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/kernel/error.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: example_eval_motion MOTION.json\n";
    return 2;
  }
  try {
    const auto motion = qmotion::io::to_motion_double(qmotion::io::read_motion(argv[1]));
    std::cout << "degree " << motion.degree() << ", " << motion.segments()
              << " segment(s), Plucker residual " << qmotion::kernel::plucker_residual(motion)
              << "\n";
    for (int i = 0; i <= 10; ++i) {
      const double t = motion.a() + (motion.b() - motion.a()) * i / 10.0;
      const auto p = qmotion::kernel::translation_vector(qmotion::kernel::evaluate(motion, t));
      std::cout << "t = " << t << "  origin at (" << p.transpose() << ")\n";
    }
  } catch (const qmotion::Error& e) {
    std::cerr << "example_eval_motion: " << e.what() << "\n";
    return e.exit_code();
  }
  return 0;
}
