/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_STRICT_XML_H_
#define GENDPDE_STRICT_XML_H_

/* Reading the plugin's XML strictly (docs/force.md, docs/integrator.md): OpenMM's SerializationNode reads a number
 * leniently (an empty string as 0, "1.0garbage" as 1, "1.5" as the integer 1, "abc" as 0), and a node may hold what
 * its version cannot. Here a value is the whole string or an error naming the object, the property and the value, and
 * a node holds only the properties and children its version defines. */

#include "openmm/OpenMMException.h"
#include "openmm/serialization/SerializationNode.h"
#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <limits>
#include <charconv>
#include <string>
#include <vector>

namespace GenDPDEPlugin {
namespace StrictXml {

/** The text of a property, or an error naming it if the node has none. */
inline std::string text(const OpenMM::SerializationNode& node, const std::string& owner, const std::string& name) {
    if (!node.hasProperty(name))
        throw OpenMM::OpenMMException(owner + " XML: the <" + node.getName() + "> element has no property '" + name
                                      + "' (corrupt, or not written by this plugin)");
    return node.getStringProperty(name);
}

/**
 * Whether the whole of text is one number of type T (double: decimal, in the C locale's format; long long: decimal
 * digits), with an optional sign, and it fits in T; result receives it. std::from_chars reads no locale and allocates
 * nothing: formatted stream input (std::istream >> value) crashed inside Python processes on a CUDA machine (a setState
 * from Python; docs/performance.md, "On a GPU"), where the C++ tests that read the same text did not.
 */
template <class T>
bool parseWhole(const std::string& text, T& result) {
    const char* begin = text.data();
    const char* end = begin + text.size();
    if (begin != end && *begin == '+' && end - begin > 1 && begin[1] != '-')
        begin++;   // from_chars takes a '-' only; a leading '+' is allowed as the C library allows it
    if (begin == end)
        return false;
    const std::from_chars_result parsed = std::from_chars(begin, end, result);
    return parsed.ec == std::errc() && parsed.ptr == end;
}

[[noreturn]] inline void refuse(const OpenMM::SerializationNode& node, const std::string& owner,
                                const std::string& name, const std::string& value, const std::string& allowed) {
    throw OpenMM::OpenMMException(owner + " XML: " + node.getName() + "." + name + " = '" + value + "' is not "
                                  + allowed);
}

/**
 * A property holding a number: the whole text a decimal number in the C locale, or inf, infinity, nan (any case,
 * signed; OpenMM writes non-finite values so): the setter it is given to then checks its range.
 */
inline double number(const OpenMM::SerializationNode& node, const std::string& owner, const std::string& name) {
    const std::string value = text(node, owner, name);
    std::string lower = value;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    const bool negative = (!lower.empty() && lower[0] == '-');
    const std::string word = (!lower.empty() && (lower[0] == '-' || lower[0] == '+')) ? lower.substr(1) : lower;
    if (word == "inf" || word == "infinity")
        return negative ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    if (word == "nan")
        return std::numeric_limits<double>::quiet_NaN();
    double result;
    if (!parseWhole(value, result))
        refuse(node, owner, name, value, "a number");
    return result + 0.0; // -0 is 0: no parameter's zero has a sign, and it is written back as "0"
}

/**
 * A property holding an integer: the whole text in the form OpenMM writes it (decimal digits without leading zeros,
 * '-' for a negative value: "04", "+4" and "-0" are refused), within the range of int.
 */
inline int integer(const OpenMM::SerializationNode& node, const std::string& owner, const std::string& name,
                   const std::string& allowed = "an integer") {
    const std::string value = text(node, owner, name);
    const size_t digits = (!value.empty() && value[0] == '-') ? 1 : 0;
    const bool canonical = value.size() > digits && value[digits] != '+'
            && (value[digits] != '0' || (value.size() == 1 && digits == 0));
    long long result;
    if (!canonical || !parseWhole(value, result) || result < INT_MIN || result > INT_MAX)
        refuse(node, owner, name, value, allowed + " (written as OpenMM writes one: no sign but '-', no leading zero)");
    return (int) result;
}

/** A property holding a flag: 0 or 1 (as OpenMM writes them), or false or true. */
inline bool boolean(const OpenMM::SerializationNode& node, const std::string& owner, const std::string& name) {
    const std::string value = text(node, owner, name);
    if (value == "1" || value == "true")
        return true;
    if (value == "0" || value == "false")
        return false;
    refuse(node, owner, name, value, "a flag: 0 or 1 (or false or true)");
}

/** How a message names an element: <name>, or the root element, whose name OpenMM's reader does not pass on. */
inline std::string elementName(const std::string& name) {
    return name.empty() ? "an element without a name (<>)" : "<" + name + ">";
}

/**
 * Refuse a property or child element that the node's version does not define: a file that says more than its version
 * can hold is corrupt or mislabelled, and what it says would otherwise be dropped silently. (A "type" property, which
 * OpenMM's serializer adds to the root and to a System's forces, is always allowed.)
 */
inline void requireOnly(const OpenMM::SerializationNode& node, const std::string& owner, int version,
                        const std::vector<std::string>& properties, const std::vector<std::string>& children) {
    const std::string where = owner + " XML (version " + std::to_string(version)
            + "): " + (node.getName().empty() ? "the root element" : "the <" + node.getName() + "> element");
    for (const auto& property : node.getProperties())
        if (property.first != "type"
            && std::find(properties.begin(), properties.end(), property.first) == properties.end())
            throw OpenMM::OpenMMException(where + " has a property '" + property.first
                                          + "' that this version does "
                                            "not define (corrupt, mislabelled, or written by a later version)");
    for (const OpenMM::SerializationNode& child : node.getChildren())
        if (std::find(children.begin(), children.end(), child.getName()) == children.end())
            throw OpenMM::OpenMMException(where + " has a child " + elementName(child.getName())
                                          + " that this version does "
                                            "not define (corrupt, mislabelled, or written by a later version)");
}

/** The child element of this name, or an error naming it if the node has none. */
inline const OpenMM::SerializationNode& child(const OpenMM::SerializationNode& node, const std::string& owner,
                                              const std::string& name) {
    for (const OpenMM::SerializationNode& c : node.getChildren())
        if (c.getName() == name)
            return c;
    throw OpenMM::OpenMMException(owner + " XML: the <" + node.getName() + "> element has no child <" + name
                                  + "> (corrupt, or not written by this plugin)");
}

} // namespace StrictXml
} // namespace GenDPDEPlugin

#endif /*GENDPDE_STRICT_XML_H_*/
