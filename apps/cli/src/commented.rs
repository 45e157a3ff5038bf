//! The commented configuration (`--print-config`, `config.toml`): every key of the TOML text
//! gets a comment with its unit and meaning, taken from the doc comments of the configuration
//! types (their `schemars::JsonSchema` derive turns each field's rustdoc into the schema's
//! `description`), so the meaning has one source: the rustdoc of the field.
//!
//! The rule the comments follow (checked by [`comment_violations`] on every study of every app,
//! documented in the user guide's conventions chapter): every key and every table header
//! written has a comment, and the comment of a key holding a floating-point number (or an
//! array of them) states a unit in brackets: `[N]`, `[m]`, `[rad/s]`, `[-]` for a
//! dimensionless number. Integers are counts or indices, dimensionless by their type.
//!
//! TOML has no null, so an optional table that a configuration leaves out (`None`) would not
//! show at all: a field that carries [`EXAMPLE_KEY`] in its schema
//! (`#[schemars(extend("x-commented-example" = TEXT))]`) is shown, when absent, as a
//! commented-out example after the configuration ([`commented_example`]).

use schemars::JsonSchema;
use serde::Serialize;
use serde_json::Value as Json;
use toml_edit::{DocumentMut, Item, Table, Value};

/// Longest comment line written (characters after `# `).
const WIDTH: usize = 96;

/// The configuration as TOML text with every key and table commented from the doc comments
/// of `C` (what `--print-config` prints and `config.toml` holds). The text reads back to the
/// same configuration as [`crate::config::to_toml`]'s: comments carry no values.
pub fn to_commented_toml<C: Serialize + JsonSchema>(config: &C) -> String {
    let text = crate::config::to_toml(config);
    let schema = schema_of::<C>();
    annotate(&text, &schema).unwrap_or(text)
}

/// The JSON schema of `C` as it is serialised (draft 2020-12, definitions under `$defs`).
pub fn schema_of<C: JsonSchema>() -> Json {
    schemars::generate::SchemaSettings::draft2020_12()
        .for_serialize()
        .into_generator()
        .into_root_schema_for::<C>()
        .to_value()
}

/// `text` (TOML) with a comment on every key and table header from `schema` (a JSON schema
/// whose `description`s are the doc comments): the field's own description, or its type's
/// when the field has none; string enumerations name their values. Keys the schema does not
/// know keep the text's decoration. Errors: `text` is not TOML.
pub fn annotate(text: &str, schema: &Json) -> Result<String, toml_edit::TomlError> {
    let mut doc: DocumentMut = text.parse()?;
    let walker = Walker { root: schema };
    let root = doc.as_table_mut();
    let mut examples = String::new();
    walker.table(root, schema, "", &mut examples);
    let mut out = String::new();
    if let Some(d) = walker.description(schema, None) {
        out.push_str(&comment_block(&d));
        out.push_str(
            "#\n# Every key is optional in a file given with --config: the file is read deeply \
             over\n# these defaults (tables merged key by key, arrays and values replaced).\n\n",
        );
    }
    out.push_str(&doc.to_string());
    out.push_str(&examples);
    Ok(out)
}

/// The schema key of a field's commented example: a string whose first line is the example's
/// heading and the others the lines of its table (see [`commented_example`]).
pub const EXAMPLE_KEY: &str = "x-commented-example";

/// The commented-out example of the table at `path` (dotted) from `example` ([`EXAMPLE_KEY`]):
/// an empty line, the heading (its first line), the table header `[path]`, the table's lines,
/// each line commented out.
pub fn commented_example(path: &str, example: &str) -> String {
    let mut lines = example.lines();
    let mut out = format!("\n# {}\n# [{path}]\n", lines.next().unwrap_or_default());
    for line in lines {
        out.push_str(&format!("# {line}\n"));
    }
    out
}

/// Schema walker: `root` holds the `$defs` that `$ref`s point into.
struct Walker<'a> {
    root: &'a Json,
}

impl<'a> Walker<'a> {
    /// `s` with its `$ref` followed (repeatedly).
    fn resolve(&self, mut s: &'a Json) -> &'a Json {
        for _ in 0..32 {
            let Some(r) = s.get("$ref").and_then(Json::as_str) else {
                return s;
            };
            let Some(name) = r.strip_prefix("#/$defs/") else {
                return s;
            };
            match self.root.get("$defs").and_then(|d| d.get(name)) {
                Some(t) => s = t,
                None => return s,
            }
        }
        s
    }

    /// The schemas `s` may stand for: itself resolved and, recursively, the alternatives and
    /// parts of its `anyOf`, `oneOf` and `allOf`.
    fn alternatives(&self, s: &'a Json, out: &mut Vec<&'a Json>) {
        let s = self.resolve(s);
        out.push(s);
        for k in ["anyOf", "oneOf", "allOf"] {
            if let Some(list) = s.get(k).and_then(Json::as_array) {
                for x in list {
                    self.alternatives(x, out);
                }
            }
        }
    }

    /// The schema of `key` in the table `table` of schema `s`: among the alternatives that
    /// have the property, the first whose constant properties (an enum's tag) match the table.
    fn property(&self, s: &'a Json, key: &str, table: &Table) -> Option<&'a Json> {
        let mut all = Vec::new();
        self.alternatives(s, &mut all);
        let with_key: Vec<&Json> = all
            .iter()
            .filter_map(|a| a.get("properties").and_then(|p| p.get(key)).map(|_| *a))
            .collect();
        let matches = |a: &&Json| {
            let Some(props) = a.get("properties").and_then(Json::as_object) else {
                return true;
            };
            props.iter().all(|(k, p)| match constant(self.resolve(p)) {
                Some(c) => table.get(k).and_then(Item::as_str).is_none_or(|v| v == c),
                None => true,
            })
        };
        let chosen = with_key
            .iter()
            .find(|a| matches(a))
            .or(with_key.first())
            .copied();
        if let Some(c) = chosen {
            return c.get("properties").and_then(|p| p.get(key));
        }
        // a map: every key has the values' schema
        all.iter()
            .find_map(|a| a.get("additionalProperties").filter(|x| x.is_object()))
    }

    /// The schema of the elements of the array schema `s`.
    fn items(&self, s: &'a Json) -> Option<&'a Json> {
        let mut all = Vec::new();
        self.alternatives(s, &mut all);
        all.iter()
            .find_map(|a| a.get("items").filter(|x| x.is_object()))
    }

    /// The text of the comment on a key of schema `s` (the field's description, else its
    /// type's), with the values of a string enumeration; `value`: the key's value, to pick an
    /// enum variant's description.
    fn description(&self, s: &'a Json, value: Option<&Item>) -> Option<String> {
        let own = s.get("description").and_then(Json::as_str);
        let resolved = self.resolve(s);
        let mut text = own
            .or_else(|| resolved.get("description").and_then(Json::as_str))
            .map(clean);
        // a string enumeration: its values, each with its description when it has one
        let mut all = Vec::new();
        self.alternatives(s, &mut all);
        let mut values: Vec<(String, Option<String>)> = Vec::new();
        for a in &all {
            if let Some(list) = a.get("enum").and_then(Json::as_array) {
                for v in list.iter().filter_map(Json::as_str) {
                    values.push((v.to_string(), None));
                }
            } else if let Some(c) = a.get("const").and_then(Json::as_str)
                && a.get("type").and_then(Json::as_str) == Some("string")
            {
                let d = a.get("description").and_then(Json::as_str).map(clean);
                values.push((c.to_string(), d));
            }
        }
        if values.len() > 1 && value.and_then(Item::as_str).is_some() {
            text = Some(with_values(text.unwrap_or_default(), &values));
        }
        text.filter(|t| !t.trim().is_empty())
    }

    /// The comment of the tag key `key` (an enum's `kind` or `law`, a constant in each
    /// variant's schema) of a table of schema `s`: the chosen variant's description and the
    /// values of the other variants, each with its description.
    fn tag_description(&self, s: &'a Json, key: &str, table: &Table) -> Option<String> {
        let value = table.get(key).and_then(Item::as_str)?;
        let mut all = Vec::new();
        self.alternatives(s, &mut all);
        let mut values: Vec<(String, Option<String>)> = Vec::new();
        for a in &all {
            let Some(c) = a
                .get("properties")
                .and_then(|p| p.get(key))
                .and_then(|p| constant(self.resolve(p)))
            else {
                continue;
            };
            if values.iter().any(|(v, _)| v == c) {
                continue;
            }
            let d = a.get("description").and_then(Json::as_str).map(clean);
            values.push((c.to_string(), d));
        }
        let chosen = values
            .iter()
            .find(|(v, _)| v == value)
            .and_then(|(_, d)| d.clone())
            .map(|d| format!("`{value}`: {d}"))
            .unwrap_or_else(|| format!("The variant: `{value}`."));
        Some(if values.len() > 1 {
            with_values(chosen, &values)
        } else {
            chosen
        })
    }

    /// Comment the keys of `table` (schema `s`, at the dotted `path`) and the tables below it;
    /// add to `examples` the commented examples of the fields it leaves out.
    fn table(&self, table: &mut Table, s: &'a Json, path: &str, examples: &mut String) {
        let within = |key: &str| {
            if path.is_empty() {
                key.to_string()
            } else {
                format!("{path}.{key}")
            }
        };
        let absent = self
            .resolve(s)
            .get("properties")
            .and_then(Json::as_object)
            .into_iter()
            .flatten()
            .filter(|(k, _)| !table.contains_key(k));
        for (key, p) in absent {
            if let Some(example) = p.get(EXAMPLE_KEY).and_then(Json::as_str) {
                examples.push_str(&commented_example(&within(key), example));
            }
        }
        let keys: Vec<String> = table.iter().map(|(k, _)| k.to_string()).collect();
        for key in keys {
            let Some(p) = self.property(s, &key, table) else {
                continue;
            };
            let comment = {
                let item = table.get(&key);
                let tag = constant(self.resolve(p)).is_some()
                    && p.get("description").is_none()
                    && self.resolve(p).get("description").is_none();
                let text = if tag {
                    self.tag_description(s, &key, table)
                } else {
                    self.description(p, item)
                };
                text.map(|d| comment_block(&d))
            };
            let Some((mut k, item)) = table.get_key_value_mut(&key) else {
                continue;
            };
            match item {
                Item::Table(sub) => {
                    if let Some(c) = &comment
                        && !sub.is_implicit()
                    {
                        sub.decor_mut().set_prefix(format!("\n{c}"));
                    }
                    self.table(sub, p, &within(&key), examples);
                }
                Item::ArrayOfTables(array) => {
                    let element = self.items(p);
                    for (i, sub) in array.iter_mut().enumerate() {
                        if let Some(c) = &comment {
                            let prefix = if i == 0 {
                                format!("\n{c}")
                            } else {
                                format!("\n# ({key}, element {})\n", i + 1)
                            };
                            sub.decor_mut().set_prefix(prefix);
                        }
                        if let Some(e) = element {
                            self.table(sub, e, &within(&key), examples);
                        }
                    }
                }
                Item::Value(_) => {
                    if let Some(c) = &comment {
                        k.leaf_decor_mut().set_prefix(c.clone());
                    }
                }
                Item::None => {}
            }
        }
    }
}

/// The value of a `const` (or one-value `enum`) string schema: an enum variant's tag.
fn constant(s: &Json) -> Option<&str> {
    s.get("const").and_then(Json::as_str).or_else(|| {
        s.get("enum")
            .and_then(Json::as_array)
            .filter(|a| a.len() == 1)
            .and_then(|a| a[0].as_str())
    })
}

/// Rustdoc markup taken out of a description: escaped brackets (`\[N\]` → `[N]`) and
/// intra-doc links (`` [`Drive`] `` → `` `Drive` ``, `[text](target)` → `text`).
fn clean(doc: &str) -> String {
    let doc = doc.replace("\\[", "\u{1}").replace("\\]", "\u{2}");
    let mut out = String::with_capacity(doc.len());
    let chars: Vec<char> = doc.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '[' {
            // a link: `[text]` followed by `(target)` or `[target]`, or `[`path`]`
            if let Some(close) = chars[i + 1..].iter().position(|&x| x == ']') {
                let inner: String = chars[i + 1..i + 1 + close].iter().collect();
                let after = i + 1 + close + 1;
                let next = chars.get(after).copied();
                let is_code = inner.starts_with('`') && inner.ends_with('`') && inner.len() > 1;
                if next == Some('(') || next == Some('[') {
                    let end = if next == Some('(') { ')' } else { ']' };
                    if let Some(c2) = chars[after + 1..].iter().position(|&x| x == end) {
                        out.push_str(&inner);
                        i = after + 1 + c2 + 1;
                        continue;
                    }
                }
                if is_code {
                    out.push_str(&inner);
                    i = after;
                    continue;
                }
            }
        }
        out.push(c);
        i += 1;
    }
    out.replace('\u{1}', "[").replace('\u{2}', "]")
}

/// `text` followed by a paragraph naming the `values` of an enumeration, each with the first
/// sentence of its description when it has one.
fn with_values(mut text: String, values: &[(String, Option<String>)]) -> String {
    let list = values
        .iter()
        .map(|(v, d)| match d {
            Some(d) => format!("`{v}`: {}", first_sentence(d)),
            None => format!("`{v}`"),
        })
        .collect::<Vec<_>>()
        .join("; ");
    if !text.is_empty() {
        text.push_str("\n\n");
    }
    text.push_str(&format!("One of {list}."));
    text
}

/// The first sentence of `text` (up to the first `. ` before a capital letter, or the end),
/// without its final full stop.
fn first_sentence(text: &str) -> String {
    let flat = text.split_whitespace().collect::<Vec<_>>().join(" ");
    let end = flat
        .match_indices(". ")
        .map(|(i, _)| i)
        .find(|&i| flat[i + 2..].starts_with(|c: char| c.is_uppercase()));
    match end {
        Some(i) => flat[..i].to_string(),
        None => flat.trim_end_matches('.').to_string(),
    }
}

/// `text` as `# ` comment lines of at most [`WIDTH`] characters, paragraphs (blank lines in
/// `text`) separated by a `#` line.
fn comment_block(text: &str) -> String {
    let mut out = String::new();
    for (n, para) in text
        .split("\n\n")
        .filter(|p| !p.trim().is_empty())
        .enumerate()
    {
        if n > 0 {
            out.push_str("#\n");
        }
        let mut line = String::new();
        for word in para.split_whitespace() {
            if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > WIDTH {
                out.push_str(&format!("# {line}\n"));
                line.clear();
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
        if !line.is_empty() {
            out.push_str(&format!("# {line}\n"));
        }
    }
    out
}

/// Where the commented configuration `text` breaks the rule of this module: the dotted paths
/// of keys and table headers without a comment, and of floating-point keys whose comment
/// states no unit in brackets (`[-]` for a dimensionless number), with what is missing.
/// Keys inside inline tables, which cannot hold comments, are named too. `Err`: `text` is not
/// TOML.
pub fn comment_violations(text: &str) -> Result<Vec<String>, toml_edit::TomlError> {
    let doc: DocumentMut = text.parse()?;
    let mut out = Vec::new();
    check_table(doc.as_table(), "", &mut out);
    Ok(out)
}

fn check_table(table: &Table, path: &str, out: &mut Vec<String>) {
    for (k, item) in table.iter() {
        let here = if path.is_empty() {
            k.to_string()
        } else {
            format!("{path}.{k}")
        };
        match item {
            Item::Table(sub) => {
                if !sub.is_implicit() && !has_comment(sub.decor().prefix()) {
                    out.push(format!("[{here}]: no comment"));
                }
                check_table(sub, &here, out);
            }
            Item::ArrayOfTables(array) => {
                for (i, sub) in array.iter().enumerate() {
                    if !has_comment(sub.decor().prefix()) {
                        out.push(format!("[[{here}]] {i}: no comment"));
                    }
                    check_table(sub, &format!("{here}[{i}]"), out);
                }
            }
            Item::Value(v) => {
                let key = table.key(k);
                let text = key
                    .and_then(|key| key.leaf_decor().prefix())
                    .and_then(|p| p.as_str())
                    .unwrap_or("")
                    .to_string()
                    + v.decor().suffix().and_then(|s| s.as_str()).unwrap_or("");
                if !text.contains('#') {
                    out.push(format!("{here}: no comment"));
                } else if holds_float(v) && !states_unit(&text) {
                    out.push(format!("{here}: no unit in brackets in its comment"));
                }
                if let Some(inline) = inline_keys(v) {
                    out.extend(
                        inline
                            .into_iter()
                            .map(|s| format!("{here}.{s}: in an inline table, no comment")),
                    );
                }
            }
            Item::None => {}
        }
    }
}

/// Whether a decoration prefix holds a comment.
fn has_comment(prefix: Option<&toml_edit::RawString>) -> bool {
    prefix
        .and_then(|p| p.as_str())
        .is_some_and(|p| p.contains('#'))
}

/// Whether `v` is a float or an array holding floats (at any depth).
fn holds_float(v: &Value) -> bool {
    match v {
        Value::Float(_) => true,
        Value::Array(a) => a.iter().any(holds_float),
        _ => false,
    }
}

/// The keys of the inline tables inside `v` (none: `None`).
fn inline_keys(v: &Value) -> Option<Vec<String>> {
    let mut keys = Vec::new();
    fn walk(v: &Value, keys: &mut Vec<String>) {
        match v {
            Value::InlineTable(t) => {
                for (k, x) in t.iter() {
                    keys.push(k.to_string());
                    walk(x, keys);
                }
            }
            Value::Array(a) => a.iter().for_each(|x| walk(x, keys)),
            _ => {}
        }
    }
    walk(v, &mut keys);
    (!keys.is_empty()).then_some(keys)
}

/// Whether a comment states a unit: a bracketed group whose content is `-` (dimensionless) or
/// holds a letter, `%` or `°` (`[N]`, `[rad/s]`, `[1/s]`, `[%]`), not a bare number range.
pub fn states_unit(comment: &str) -> bool {
    let mut rest = comment;
    while let Some(open) = rest.find('[') {
        let after = &rest[open + 1..];
        let Some(close) = after.find(']') else {
            return false;
        };
        let inner = after[..close].trim();
        if inner == "-"
            || inner
                .chars()
                .any(|c| c.is_alphabetic() || c == '%' || c == '°')
        {
            return true;
        }
        rest = &after[close + 1..];
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rustdoc_markup_is_taken_out() {
        assert_eq!(
            clean("Tension \\[N\\] of [`Drive`]"),
            "Tension [N] of `Drive`"
        );
        assert_eq!(
            clean("see [the guide](x.md) and [`a`](b)"),
            "see the guide and `a`"
        );
        assert_eq!(clean("[x, y] \\[m\\]"), "[x, y] [m]");
    }

    #[test]
    fn units_are_recognised() {
        for yes in ["# a [N]", "# [-]", "# x [rad/s]", "# [1/s]", "# [%]"] {
            assert!(states_unit(yes), "{yes}");
        }
        for no in ["# a", "# range [0, 1]", "# [x"] {
            assert!(!states_unit(no), "{no}");
        }
    }

    /// A configuration of every shape: nested table, array of tables, internally tagged enum,
    /// optional table, string enumeration.
    mod demo {
        use serde::{Deserialize, Serialize};

        /// The demo drive.
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(deny_unknown_fields)]
        pub struct Drive {
            /// Installation tension \[N\].
            pub tension: f64,
            /// Number of spans.
            pub spans: usize,
            /// The belt model.
            pub model: Model,
            /// Pulleys in travel order.
            pub pulleys: Vec<Pulley>,
            /// Optional tensioner.
            #[serde(skip_serializing_if = "Option::is_none")]
            pub tensioner: Option<Tensioner>,
        }

        /// A pulley.
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(deny_unknown_fields)]
        pub struct Pulley {
            /// Radius \[m\].
            pub radius: f64,
            /// What turns it.
            pub load: Load,
        }

        /// The load of a pulley.
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
        pub enum Load {
            /// Free.
            None,
            /// A constant torque.
            Torque {
                /// The torque \[N m\].
                torque: f64,
            },
            /// A constant speed.
            Speed {
                /// The speed \[rad/s\].
                speed: f64,
            },
        }

        /// A tensioner.
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(deny_unknown_fields)]
        pub struct Tensioner {
            /// Arm length \[m\] of the [`Drive`].
            pub arm: f64,
        }

        /// Belt model.
        #[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(rename_all = "lowercase")]
        pub enum Model {
            /// Flowing mesh.
            Flowing,
            /// ANCF elements.
            Ancf,
        }

        pub fn drive() -> Drive {
            Drive {
                tension: 400.0,
                spans: 2,
                model: Model::Flowing,
                pulleys: vec![
                    Pulley {
                        radius: 0.05,
                        load: Load::Speed { speed: 60.0 },
                    },
                    Pulley {
                        radius: 0.1,
                        load: Load::Torque { torque: 3.0 },
                    },
                    Pulley {
                        radius: 0.02,
                        load: Load::None,
                    },
                ],
                tensioner: Some(Tensioner { arm: 0.08 }),
            }
        }
    }

    // every key and table commented with the right variant's doc, units kept, markup gone,
    // and the text reads back to the same value
    #[test]
    fn every_key_is_commented_and_reads_back() {
        let d = demo::drive();
        let text = to_commented_toml(&d);
        assert_eq!(
            comment_violations(&text).unwrap(),
            Vec::<String>::new(),
            "{text}"
        );
        for line in [
            "# Installation tension [N].\ntension = 400.0",
            "# Number of spans.\nspans = 2",
            "# The speed [rad/s].\nspeed = 60.0",
            "# The torque [N m].\ntorque = 3.0",
            "# Arm length [m] of the `Drive`.\narm = 0.08",
            "One of `flowing`: Flowing mesh; `ancf`: ANCF elements.\nmodel = \"flowing\"",
            "# `speed`: A constant speed.\n#\n# One of `none`: Free; `torque`: A constant torque; `speed`: A constant speed.\nkind = \"speed\"",
            "# Pulleys in travel order.\n[[pulleys]]",
            "# The demo drive.",
        ] {
            assert!(text.contains(line), "{line:?} not in\n{text}");
        }
        let back: demo::Drive = toml::from_str(&text).unwrap();
        assert_eq!(back, d);
        // a key without a comment, and a float without a unit, are named
        let bare = crate::config::to_toml(&d);
        let v = comment_violations(&bare).unwrap();
        assert!(v.iter().any(|x| x == "tension: no comment"), "{v:?}");
        let v = comment_violations("# the tension\ntension = 1.0\n# count\nn = 2\n").unwrap();
        assert_eq!(
            v,
            vec!["tension: no unit in brackets in its comment".to_string()]
        );
    }

    #[test]
    fn comment_lines_are_wrapped() {
        let c = comment_block(&"word ".repeat(60));
        assert!(
            c.lines()
                .all(|l| l.len() <= WIDTH + 2 && l.starts_with("# "))
        );
        assert_eq!(comment_block("a\n\nb"), "# a\n#\n# b\n");
    }
}
