// SPDX-License-Identifier: MIT
#pragma once
// The `truth` argument of identify(): the true parameter values printed beside the identified ones, as
// `jacobid identify --truth FILE` adds them.
#include <pybind11/pybind11.h>

#include <map>
#include <string>
#include <vector>

namespace jacobid::python {

// `value` as parameter name -> value: a dict of finite numbers, simulate()'s result (its "parameters"), or the
// path (str, bytes, os.PathLike) of simulate --truth's JSON file. As the command line requires of --truth, it
// must hold exactly the model's `parameters`: an unknown name is refused naming it, the closest known name and
// all of them, a missing one naming it (the truth of another robot or parameter set gave errors of hundreds of
// percent against unrelated values), a value that is not a finite number naming its key.
std::map<std::string, double> truth_values(const pybind11::handle& value, const std::vector<std::string>& parameters);

}  // namespace jacobid::python
