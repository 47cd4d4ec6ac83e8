/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_MESSAGE_TEXT_H_
#define GENDPDE_MESSAGE_TEXT_H_

/* The text of the plugin's error messages, written without iostreams. Formatted stream output (std::ostringstream <<
 * double) crashed inside Python processes on a CUDA machine whose compiler (GCC 13) was newer than the one OpenMM's
 * wheel was built with, while the C++ tests on the same machine formatted the same numbers (docs/performance.md, "On a
 * GPU"); std::to_chars reads no locale and needs no stream. The numbers come out as an ostream writes them by default:
 * integers in decimal, doubles as printf's %.<precision>g (precision 6 unless set). */

#include <charconv>
#include <string>
#include <type_traits>

namespace GenDPDEPlugin {

class MessageText {
public:
    /** The significant digits of the doubles written from now on, as std::ostream::precision. */
    void precision(int digits) { significantDigits = digits; }
    MessageText& operator<<(const std::string& text) {
        message += text;
        return *this;
    }
    MessageText& operator<<(const char* text) {
        message += text;
        return *this;
    }
    MessageText& operator<<(char c) {
        message += c;
        return *this;
    }
    template <class Integer, std::enable_if_t<std::is_integral<Integer>::value, int> = 0>
    MessageText& operator<<(Integer value) {
        message += std::to_string(value);
        return *this;
    }
    MessageText& operator<<(double value) {
        char buffer[64];
        const std::to_chars_result written =
                std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general, significantDigits);
        message.append(buffer, written.ptr);
        return *this;
    }
    const std::string& str() const { return message; }

private:
    std::string message;
    int significantDigits = 6;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_MESSAGE_TEXT_H_*/
