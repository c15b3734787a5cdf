//! The client's tests: lenient reading of completions, `${VAR:-default}` expansion, option checks.

use super::*;

#[test]
fn completions_are_read_leniently() {
    let ok = json!({"choices": [{"message": {"content": "hi"}}], "usage": {"prompt_tokens": 3, "completion_tokens": 1}});
    assert_eq!(read_completion(&ok).unwrap(), ("hi".into(), 3, 1));
    let parts = json!({"choices": [{"message": {"content": [{"type": "text", "text": "a"}, {"type": "text", "text": "b"}]}}]});
    assert_eq!(read_completion(&parts).unwrap().0, "ab");
    let reasoning = json!({"choices": [{"message": {"content": "", "reasoning_content": "{}"}}]});
    assert_eq!(read_completion(&reasoning).unwrap().0, "{}");
    assert!(
        read_completion(&json!({"choices": []}))
            .unwrap_err()
            .contains("empty")
    );
    assert!(
        read_completion(&json!({"error": {"message": "overloaded"}}))
            .unwrap_err()
            .contains("overloaded")
    );
}

#[test]
fn env_expansion_with_default() {
    assert_eq!(
        expand_env("${DISCO_SURELY_UNSET_VAR:-http://127.0.0.1:8080/v1}"),
        "http://127.0.0.1:8080/v1"
    );
    assert_eq!(expand_env("plain"), "plain");
}

#[test]
fn options_are_checked() {
    let mut t = toml::Table::new();
    t.insert("temperature".into(), toml::Value::Float(0.0));
    t.insert("max_tokens".into(), toml::Value::Integer(300));
    let s = ClientSettings::from_options(&t).unwrap();
    assert_eq!((s.temperature, s.max_tokens), (0.0, 300));
    t.insert("temprature".into(), toml::Value::Float(0.0));
    assert!(
        ClientSettings::from_options(&t)
            .unwrap_err()
            .contains("temprature")
    );
}

/// reqwest carries no TLS provider of its own here (ring is installed by `from_config`): an
/// https model URL must give a client, and a server that does not speak TLS a clean error.
#[tokio::test]
async fn an_https_model_gets_a_tls_client_and_a_plain_server_a_clean_error() {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let port = listener.local_addr().unwrap().port();
    tokio::spawn(async move {
        while let Ok((mut socket, _)) = listener.accept().await {
            use tokio::io::AsyncWriteExt;
            let _ = socket.write_all(b"HTTP/1.1 200 OK\r\n\r\nnot tls").await;
        }
    });
    let model: ModelConfig = toml::from_str(&format!(
        "base_url = \"https://127.0.0.1:{port}/v1\"\noptions = {{ retries = 0, timeout_s = 5 }}"
    ))
    .unwrap();
    let client = ChatClient::from_config("m", &model, None, None).expect("a TLS client builds");
    let (err, _) = client
        .chat("test", &[Message::text("user", "hi")], None)
        .await
        .expect_err("a plain-text server cannot finish a TLS handshake");
    assert!(!err.to_string().is_empty());
}
