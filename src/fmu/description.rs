//! `modelDescription.xml` of an FMU (FMI 2.0 standard, 2014, chapter 2.2 and 4.3.1): the
//! co-simulation capabilities, unit definitions, default experiment, the scalar variables of
//! [`super::variables`] and the model structure (outputs and initial unknowns).

use super::{Causality, Config, FMI_VERSION, Variable};
use std::fmt::Write;

/// The FMI unit name and SI base-unit exponents `(kg, m, s, rad)` of a wbv unit; a unit whose
/// exponents are not integers (`m/s^1.75`) has none (FMI 2.0 allows a unit without `BaseUnit`).
pub fn unit(wbv_unit: &str) -> (String, Option<[i32; 4]>) {
    let base = match wbv_unit {
        "m/s²" => Some([0, 1, -2, 0]),
        "N" => Some([1, 1, -2, 0]),
        "kg" => Some([1, 0, 0, 0]),
        "N/m" => Some([1, 0, -2, 0]),
        "N·s/m" => Some([1, 0, -1, 0]),
        "N/m³" => Some([1, -2, -2, 0]),
        "m" => Some([0, 1, 0, 0]),
        "m/s" => Some([0, 1, -1, 0]),
        "1" => Some([0, 0, 0, 0]),
        "kg·m²" => Some([1, 2, 0, 0]),
        "N·m/rad" => Some([1, 2, -2, -1]),
        "N·m·s/rad" => Some([1, 2, -1, -1]),
        "m²" => Some([0, 2, 0, 0]),
        "Hz" => Some([0, 0, -1, 0]),
        "Pa" => Some([1, -1, -2, 0]),
        "rad/s²" => Some([0, 0, -2, 1]),
        "N·m" => Some([1, 2, -2, 0]),
        _ => None,
    };
    let name = wbv_unit
        .replace('²', "2")
        .replace('³', "3")
        .replace('·', ".")
        .replace('^', "");
    (name, base)
}

/// `s` escaped for an XML attribute.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&apos;")
}

/// A C identifier for the model: `wbv_` and the model name with every other character `_`; the
/// shared library in `binaries/linux64/` carries this name.
pub fn model_identifier(model: &str) -> String {
    let body: String = model
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    format!("wbv_{body}")
}

/// A GUID (`{8-4-4-4-12}` hexadecimal) that is a hash of `text`: the same FMU content gives the
/// same GUID, any change a different one.
pub fn guid_of(text: &str) -> String {
    use std::hash::{Hash, Hasher};
    let mut words = [0u64; 2];
    for (seed, w) in words.iter_mut().enumerate() {
        let mut h = std::hash::DefaultHasher::new();
        (seed, text).hash(&mut h);
        *w = h.finish();
    }
    let hex = format!("{:016x}{:016x}", words[0], words[1]);
    format!(
        "{{{}-{}-{}-{}-{}}}",
        &hex[0..8],
        &hex[8..12],
        &hex[12..16],
        &hex[16..20],
        &hex[20..32]
    )
}

/// The text of `modelDescription.xml` for `variables` of the model described by `description`,
/// under `config` (its `guid` is written as it is).
pub fn xml(config: &Config, description: &str, variables: &[Variable]) -> String {
    let mut x = String::new();
    let version = env!("CARGO_PKG_VERSION");
    let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        x,
        r#"<fmiModelDescription fmiVersion="{FMI_VERSION}" modelName="{}" guid="{}" description="{}" version="{version}" generationTool="wbv {version}" variableNamingConvention="flat" numberOfEventIndicators="0">"#,
        escape(&config.model),
        escape(&config.guid),
        escape(description)
    );
    let _ = writeln!(
        x,
        r#"  <CoSimulation modelIdentifier="{}" needsExecutionTool="false" canHandleVariableCommunicationStepSize="true" canInterpolateInputs="false" maxOutputDerivativeOrder="0" canRunAsynchronuously="false" canBeInstantiatedOnlyOncePerProcess="false" canNotUseMemoryManagementFunctions="true" canGetAndSetFMUstate="true" canSerializeFMUstate="true" providesDirectionalDerivative="false"/>"#,
        model_identifier(&config.model)
    );
    let mut units: Vec<&str> = variables.iter().map(|v| v.unit).collect();
    units.sort_unstable();
    units.dedup();
    x.push_str("  <UnitDefinitions>\n");
    for u in units {
        let (name, base) = unit(u);
        match base {
            Some([kg, m, s, rad]) => {
                let mut attrs = String::new();
                for (k, e) in [("kg", kg), ("m", m), ("s", s), ("rad", rad)] {
                    if e != 0 {
                        let _ = write!(attrs, r#" {k}="{e}""#);
                    }
                }
                let _ = writeln!(
                    x,
                    r#"    <Unit name="{}"><BaseUnit{attrs}/></Unit>"#,
                    escape(&name)
                );
            }
            None => {
                let _ = writeln!(x, r#"    <Unit name="{}"/>"#, escape(&name));
            }
        }
    }
    x.push_str("  </UnitDefinitions>\n");
    x.push_str("  <LogCategories>\n    <Category name=\"logStatusError\" description=\"errors: bad input, step or parameter\"/>\n  </LogCategories>\n");
    let _ = writeln!(
        x,
        r#"  <DefaultExperiment startTime="0" stepSize="{}"/>"#,
        config.dt
    );
    x.push_str("  <ModelVariables>\n");
    for v in variables {
        let (causality, variability, initial) = match v.causality {
            Causality::Input => ("input", "continuous", ""),
            Causality::Output => ("output", "continuous", r#" initial="calculated""#),
            Causality::Parameter => ("parameter", "fixed", r#" initial="exact""#),
        };
        let start = v
            .start
            .map_or(String::new(), |s| format!(r#" start="{s:?}""#));
        let _ = writeln!(
            x,
            r#"    <ScalarVariable name="{}" valueReference="{}" description="{}" causality="{causality}" variability="{variability}"{initial}><Real{start} unit="{}"/></ScalarVariable>"#,
            escape(&v.name),
            v.vr,
            escape(&v.description),
            escape(&unit(v.unit).0)
        );
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    let outputs: Vec<usize> = (variables.iter().enumerate())
        .filter(|(_, v)| v.causality == Causality::Output)
        .map(|(i, _)| i + 1)
        .collect();
    for tag in ["Outputs", "InitialUnknowns"] {
        let _ = writeln!(x, "    <{tag}>");
        for i in &outputs {
            let _ = writeln!(x, r#"      <Unknown index="{i}"/>"#);
        }
        let _ = writeln!(x, "    </{tag}>");
    }
    x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
    x
}
