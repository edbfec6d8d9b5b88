/// \file
/// The error that refuses bad input: the function, the field and what is wrong with it.
#pragma once

#include <stdexcept>
#include <string>

namespace cyclone {

/// Bad input refused by a cyclone call. what() reads
/// "<function>: <field> <problem>", e.g.
/// "World::addBody: shape.radius must be finite and > 0, got -1".
/// The object refusing it is unchanged after the throw.
class InvalidArgument : public std::invalid_argument {
public:
    /// An error of `function` about `field`; what() is "function: field problem".
    InvalidArgument(std::string function, std::string field, std::string problem)
        : std::invalid_argument(function + ": " + field + " " + problem),
          function_(std::move(function)),
          field_(std::move(field)),
          problem_(std::move(problem)) {}

    /// The refusing function, e.g. "World::addBody".
    const std::string &function() const { return function_; }
    /// The offending field as a path, e.g. "shape.half_extents[1]".
    const std::string &field() const { return field_; }
    /// What is wrong with it, e.g. "must be finite and > 0, got -1".
    const std::string &problem() const { return problem_; }

private:
    std::string function_;
    std::string field_;
    std::string problem_;
};

}  // namespace cyclone
