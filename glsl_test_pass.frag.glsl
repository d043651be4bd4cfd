// a pass
void main() {
}
