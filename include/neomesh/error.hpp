// neomesh::Error — the one exception type the library throws. Its message is a complete
// sentence a user can act on ("in.msh: cell 1843 is inverted (det J = -0.02)"); it never names
// a command-line option.
#pragma once

#include <stdexcept>
#include <string>

namespace neomesh {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An option struct's field out of range (SmoothOptions::validate(), ...): `field()` is its
// path ("energy.lambda"), `what()` the whole sentence ("energy.lambda must be positive (got
// -1)"), `requirement()` the part after the field ("must be positive (got -1)"), so that a
// front end can name its own spelling of the option.
class OptionError : public Error {
 public:
  OptionError(std::string field, std::string requirement)
      : Error(field + " " + requirement),
        field_(std::move(field)),
        requirement_(std::move(requirement)) {}
  const std::string& field() const { return field_; }
  const std::string& requirement() const { return requirement_; }

 private:
  std::string field_, requirement_;
};

}  // namespace neomesh
