// io/cli/main.cpp: the qmotion executable.
#include <exception>
#include <iostream>
#include <qmotion/io/cli/commands.hpp>
#include <qmotion/kernel/error.hpp>

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
