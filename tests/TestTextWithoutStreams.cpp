/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The message text and the XML numbers written and read without iostreams (MessageText.h, StrictXml.h) against
 * std::ostringstream and std::istringstream in the classic locale, which they replace: the same text for every kind
 * of number the messages and files hold. */

#include "TestUtilities.h"
#include "internal/MessageText.h"
#include "internal/StrictXml.h"
#include "openmm/OpenMMException.h"
#include <climits>
#include <cmath>
#include <limits>
#include <locale>
#include <sstream>
#include <string>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

const std::vector<double> doubles = {0.0,
                                     -0.0,
                                     1.0,
                                     -1.0,
                                     0.1,
                                     1.0 / 3.0,
                                     2.0 / 3.0,
                                     123456.789,
                                     1234567.0,
                                     1e-5,
                                     1e-4,
                                     9.9999995e-5,
                                     1e21,
                                     6.02214076e23,
                                     8.314462618,
                                     5e-324,
                                     2.2250738585072014e-308,
                                     1.7976931348623157e308,
                                     0.001,
                                     10000.0,
                                     125.7,
                                     -273.15,
                                     std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(),
                                     std::numeric_limits<double>::quiet_NaN()};

void testMessageTextWritesWhatAStreamWrites() {
    for (int precision : {0, 1, 6, 12, 17}) {
        for (double value : doubles) {
            std::ostringstream stream;
            stream.imbue(std::locale::classic());
            MessageText text;
            if (precision > 0) {   // (0: the default precision, 6, never set)
                stream.precision(precision);
                text.precision(precision);
            }
            stream << "x = " << value << " at step " << 123456789012LL << ", particle " << 7 << ' '
                   << std::string("nm");
            text << "x = " << value << " at step " << 123456789012LL << ", particle " << 7 << ' ' << std::string("nm");
            if (text.str() != stream.str())
                throw OpenMMException("MessageText wrote '" + text.str() + "' where a stream writes '" + stream.str()
                                      + "'");
        }
    }
}

void testStrictNumbersReadWhatAStreamReads() {
    const std::vector<std::string> accepted = {"0",
                                               "-0",
                                               "1",
                                               "+1",
                                               "-1",
                                               "0.1",
                                               ".5",
                                               "5.",
                                               "1e3",
                                               "1E3",
                                               "-2.5e-3",
                                               "+2.5e+3",
                                               "0.33333333333333331",
                                               "1.7976931348623157e308",
                                               "2.2250738585072014e-308",
                                               "125.7",
                                               "1234567890123456789"};
    for (const std::string& text : accepted) {
        std::istringstream stream(text);
        stream.imbue(std::locale::classic());
        double expected;
        stream >> std::noskipws >> expected;
        double found;
        if (!StrictXml::parseWhole(text, found) || found != expected || std::signbit(found) != std::signbit(expected))
            throw OpenMMException("StrictXml::parseWhole('" + text + "') differs from a stream's reading");
    }
    const std::vector<std::string> refused = {"",    " 1",  "1 ", "1.0garbage", "abc",   "+",  "-",
                                              "+-1", "--1", "1e", "0x10",       "1e999", "1,5"};
    for (const std::string& text : refused) {
        double found;
        if (StrictXml::parseWhole(text, found))
            throw OpenMMException("StrictXml::parseWhole accepted '" + text + "' as a number");
    }
    const std::vector<std::pair<std::string, long long>> integers = {{"0", 0},
                                                                     {"7", 7},
                                                                     {"+7", 7},
                                                                     {"-7", -7},
                                                                     {"2147483647", INT_MAX},
                                                                     {"-2147483648", INT_MIN},
                                                                     {"9223372036854775807", LLONG_MAX}};
    for (const auto& c : integers) {
        long long found;
        if (!StrictXml::parseWhole(c.first, found) || found != c.second)
            throw OpenMMException("StrictXml::parseWhole('" + c.first + "') is not " + std::to_string(c.second));
    }
    for (const char* text : {"", "1.5", "1e3", " 1", "1 ", "abc", "+-1", "9223372036854775808"}) {
        long long found;
        if (StrictXml::parseWhole(std::string(text), found))
            throw OpenMMException("StrictXml::parseWhole accepted '" + std::string(text) + "' as an integer");
    }
}

int main() {
    return runTestProgram([]() {
        testMessageTextWritesWhatAStreamWrites();
        testStrictNumbersReadWhatAStreamReads();
    });
}
