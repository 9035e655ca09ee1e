// Parameter files: a flat YAML mapping of scalars (the shape `rosparam load` puts under a node's
// private namespace), read into the key -> text map every ParameterTable applies.
#ifndef HEX_SLAM_IO_PARAMETER_FILE_H_
#define HEX_SLAM_IO_PARAMETER_FILE_H_

#include <map>
#include <string>

namespace hex_slam {
namespace io {

// Returns an empty string or an error (unreadable file, one over 1 MiB, bad YAML, a value that is
// not a scalar).
std::string ReadParameterFile(const std::string& path, std::map<std::string, std::string>* values);
// The same from the file's text; `name` names it in errors.
std::string ParseParameterText(const std::string& text, const std::string& name,
                               std::map<std::string, std::string>* values);

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_PARAMETER_FILE_H_
