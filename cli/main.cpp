// cli/main.cpp: the qmotion executable: runs the command line (run.cpp) and maps
// errors to the exit statuses of docs/formats.md.
#include <exception>
#include <iostream>
#include <qmotion/kernel/error.hpp>

#include "command.hpp"

int main(int argc, char** argv) {
  try {
    return qmotion::cli::run(argc, argv);
  } catch (const qmotion::Error& e) {
    std::cerr << "qmotion: error: " << e.what() << '\n';
    return e.exit_code();
  } catch (const std::exception& e) {
    std::cerr << "qmotion: internal error: " << e.what() << '\n';
    return 1;
  }
}
