//! `value_enum!`: a closed set of named values (a technique, a traversal path, a splat kernel, …)
//! that the scene's `[caustics]` table, the bench configs and the command line all read by the
//! same names. It derives the name table once and, from it, `Display`, `FromStr`, serde (an
//! unknown name is serde's "unknown variant" error, which the TOML parser places on its key and
//! line) and clap's `ValueEnum` (so `--help` lists the possible values, each with its doc line).

/// Declares `pub enum $name` with each variant's name as it is written in files and on the
/// command line, and its doc comment as its help line.
macro_rules! value_enum {
    (
        $(#[doc = $doc:literal])*
        pub enum $name:ident {
            $( $(#[doc = $vdoc:literal])* $variant:ident = $text:literal, )+
        }
    ) => {
        $(#[doc = $doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum $name {
            $( $(#[doc = $vdoc])* $variant, )+
        }

        impl $name {
            /// Every value, in declaration order.
            pub const ALL: &'static [$name] = &[$($name::$variant),+];
            /// Every value's name, in declaration order.
            pub const NAMES: &'static [&'static str] = &[$($text),+];

            /// The name in files and on the command line.
            pub fn name(self) -> &'static str {
                match self {
                    $($name::$variant => $text,)+
                }
            }

            /// The value called `name`, if there is one.
            pub fn parse(name: &str) -> Option<$name> {
                match name {
                    $($text => Some($name::$variant),)+
                    _ => None,
                }
            }

            /// The doc comment of the value (its help line).
            pub fn help(self) -> &'static str {
                match self {
                    $($name::$variant => concat!("" $(, $vdoc)*).trim(),)+
                }
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $name {
            type Err = String;
            fn from_str(s: &str) -> Result<$name, String> {
                $name::parse(s).ok_or_else(|| {
                    format!("unknown value `{s}`; expected one of {}", $name::NAMES.join(", "))
                })
            }
        }

        impl serde::Serialize for $name {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        impl<'de> serde::Deserialize<'de> for $name {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<$name, D::Error> {
                let s = <String as serde::Deserialize>::deserialize(d)?;
                $name::parse(&s).ok_or_else(|| <D::Error as serde::de::Error>::unknown_variant(&s, $name::NAMES))
            }
        }

        impl clap::ValueEnum for $name {
            fn value_variants<'a>() -> &'a [$name] {
                $name::ALL
            }
            fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
                let v = clap::builder::PossibleValue::new(self.name());
                Some(if self.help().is_empty() { v } else { v.help(self.help()) })
            }
        }
    };
}

pub(crate) use value_enum;
