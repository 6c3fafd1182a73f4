#include "core/pet/PetDisplay.h"

#include "core/pet/SuvParameters.h"

namespace lucent {

std::string PetDisplay::unit() const {
    if (inSuv()) {
        return "SUVbw";
    }
    if (storedUnits == "BQML") {
        return "Bq/mL";
    }
    if (storedUnits == "CNTS") {
        return "counts";
    }
    return storedUnits;
}

std::string PetDisplay::ucum() const {
    if (inSuv()) {
        return "{SUVbw}g/ml";
    }
    if (storedUnits == "BQML") {
        return "Bq/ml";
    }
    if (storedUnits.empty()) {
        return "1";
    }
    return "{" + unit() + "}";
}

PetDisplay petDisplayOf(const SuvParameters& parameters) {
    PetDisplay display;
    display.storedUnits = parameters.units;
    if (parameters.units == "GML") {
        display.suvFactor = 1.0; // the values are SUVbw already
        return display;
    }
    try {
        display.suvFactor = suvBwFactor(parameters);
    } catch (const SuvError& e) {
        display.refusal = e.what();
    }
    return display;
}

std::string petDisplayNotice(const PetDisplay& display) {
    if (display.inSuv()) {
        return {};
    }
    const std::string unit = display.unit().empty() ? "stored units" : display.unit();
    return "PT series shown in " + unit + ", not in SUVbw: " + display.refusal;
}

} // namespace lucent
