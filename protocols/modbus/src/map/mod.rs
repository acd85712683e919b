//! Declarative register maps (`fixtures/modbus/*.toml`): the file format, its compiler and the
//! value codec.

pub mod value;
